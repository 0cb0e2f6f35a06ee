#include "scaling/richardson.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace cgdem::scaling {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ln g(p) of eq. (1), written with expm1 so that it stays accurate for small p.
double log_g(double p, double ln21, double ln32) {
  return p * ln21 + std::log(std::expm1(p * ln32)) - std::log(std::expm1(p * ln21));
}

void sort_by_h(std::vector<Level>& v) {
  for (const Level& l : v) {
    if (!(l.h > 0) || !std::isfinite(l.h)) throw Error(fmt::format("richardson: h = {:g} is not a positive number", l.h));
    if (!std::isfinite(l.f)) throw Error(fmt::format("richardson: the value at h = {:g} is {:g}", l.h, l.f));
  }
  std::sort(v.begin(), v.end(), [](const Level& a, const Level& b) { return a.h < b.h; });
  for (size_t i = 1; i < v.size(); ++i)
    if (!(v[i].h > v[i - 1].h)) throw Error(fmt::format("richardson: two levels share h = {:g}", v[i].h));
}

}  // namespace

std::string to_string(Behaviour b) {
  switch (b) {
    case Behaviour::Monotone: return "monotone";
    case Behaviour::Oscillatory: return "oscillatory";
    case Behaviour::Divergent: return "divergent";
    case Behaviour::Flat: return "flat";
  }
  return "?";
}

double observed_order(double ratio, double r21, double r32) {
  if (!(r21 > 1) || !(r32 > 1) || !(ratio > 0) || !std::isfinite(ratio)) return kNaN;
  const double ln21 = std::log(r21), ln32 = std::log(r32), target = std::log(ratio);
  if (std::fabs(ln21 - ln32) <= 1e-14 * ln21) {  // constant ratio: eq. (2)
    const double p = target / ln21;
    return (p > 0 && p <= kMaxOrder) ? p : kNaN;
  }
  // Bisection on the monotone ln g(p) - ln(ratio) over (0, kMaxOrder]; g(0+) = ln32/ln21.
  if (target <= std::log(ln32 / ln21)) return kNaN;
  double lo = 0, hi = kMaxOrder;
  if (log_g(hi, ln21, ln32) < target) return kNaN;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (log_g(mid, ln21, ln32) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TripleResult analyse_triple(Level a, Level b, Level c, double rel_roundoff) {
  std::vector<Level> v{a, b, c};
  sort_by_h(v);
  TripleResult t;
  t.fine = v[0], t.medium = v[1], t.coarse = v[2];
  t.r21 = v[1].h / v[0].h;
  t.r32 = v[2].h / v[1].h;
  const double f1 = v[0].f, f2 = v[1].f, f3 = v[2].f;
  t.spread = std::max({f1, f2, f3}) - std::min({f1, f2, f3});
  t.order = t.extrapolated = t.gci_fine = t.gci_fine_rel = kNaN;
  const double e21 = f2 - f1, e32 = f3 - f2;
  const double zero = rel_roundoff * std::max({std::fabs(f1), std::fabs(f2), std::fabs(f3)});
  if (std::fabs(e21) <= zero) {
    t.behaviour = Behaviour::Flat;
    return t;
  }
  const double ratio = e32 / e21;
  if (ratio < 0 && std::fabs(e32) > zero) {
    t.behaviour = Behaviour::Oscillatory;
    return t;
  }
  if (ratio <= std::log(t.r32) / std::log(t.r21)) {  // p <= 0, including e32 at round-off
    t.behaviour = Behaviour::Divergent;
    return t;
  }
  const double p = observed_order(ratio, t.r21, t.r32);
  if (std::isnan(p)) {  // root above kMaxOrder: the fine pair agrees far better than the model
    t.behaviour = Behaviour::Flat;
    return t;
  }
  t.behaviour = Behaviour::Monotone;
  t.order = p;
  const double d21 = std::pow(t.r21, p) - 1;
  t.extrapolated = f1 + (f1 - f2) / d21;                   // Celik eq. 5
  t.gci_fine = kGciSafetyFactor * std::fabs(e21) / d21;    // Celik eq. 7 (absolute)
  if (f1 != 0) t.gci_fine_rel = t.gci_fine / std::fabs(f1);
  return t;
}

std::vector<TripleResult> analyse_sequence(std::vector<Level> levels, double rel_roundoff) {
  sort_by_h(levels);
  std::vector<TripleResult> out;
  for (size_t i = 0; i + 2 < levels.size(); ++i)
    out.push_back(analyse_triple(levels[i], levels[i + 1], levels[i + 2], rel_roundoff));
  return out;
}

PowerFit fit_error_power_law(std::vector<Level> levels, double exact) {
  sort_by_h(levels);
  PowerFit fit;
  std::vector<double> x, y;
  int last_sign = 0;
  for (const Level& l : levels) {
    const double e = l.f - exact;
    if (e == 0) continue;
    const int sign = e > 0 ? 1 : -1;
    if (last_sign != 0 && sign != last_sign) ++fit.sign_changes;
    last_sign = sign;
    x.push_back(std::log(l.h));
    y.push_back(std::log(std::fabs(e)));
  }
  fit.levels = static_cast<int>(x.size());
  if (fit.levels < 2) {
    fit.order = fit.constant = fit.max_log_residual = kNaN;
    return fit;
  }
  // Ordinary least squares, slope = cov(x, y) / var(x).
  const double n = fit.levels;
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  fit.order = sxy / sxx;
  const double ln_c = my - fit.order * mx;
  fit.constant = std::exp(ln_c);
  for (size_t i = 0; i < x.size(); ++i)
    fit.max_log_residual = std::max(fit.max_log_residual, std::fabs(y[i] - ln_c - fit.order * x[i]));
  return fit;
}

}  // namespace cgdem::scaling
