#include "scaling/series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace cgdem::scaling {

std::vector<double> resample(const Series& s, const std::vector<double>& times) {
  const size_t n = s.t.size();
  if (n == 0 || s.y.size() != n) throw Error("resample: empty series or t and y of different lengths");
  for (size_t i = 1; i < n; ++i)
    if (!(s.t[i] > s.t[i - 1])) throw Error(fmt::format("resample: times not increasing at sample {} (t = {:g})", i, s.t[i]));
  const double tol = 1e-9 * std::max(1e-300, std::fabs(s.t.back() - s.t.front()));
  std::vector<double> out(times.size());
  size_t k = 0;
  for (size_t j = 0; j < times.size(); ++j) {
    const double tau = times[j];
    if (tau < s.t.front() - tol || tau > s.t.back() + tol)
      throw Error(fmt::format("resample: t = {:g} outside the series' span [{:g}, {:g}]", tau, s.t.front(), s.t.back()));
    if (n == 1) {
      out[j] = s.y[0];
      continue;
    }
    // Interval [t_k, t_{k+1}] holding tau (times are usually increasing: k moves forward).
    if (k + 1 >= n || tau < s.t[k]) k = 0;
    while (k + 2 < n && tau > s.t[k + 1]) ++k;
    const double a = std::clamp((tau - s.t[k]) / (s.t[k + 1] - s.t[k]), 0.0, 1.0);
    out[j] = (1 - a) * s.y[k] + a * s.y[k + 1];
  }
  return out;
}

std::vector<double> common_times(const std::vector<double>& reference, const std::vector<Series>& all) {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (const auto& s : all) {
    if (s.t.empty()) return {};
    lo = std::max(lo, s.t.front());
    hi = std::min(hi, s.t.back());
  }
  const double tol = 1e-9 * std::max(1e-300, std::fabs(hi - lo));
  std::vector<double> out;
  for (double t : reference)
    if (t >= lo - tol && t <= hi + tol) out.push_back(t);
  return out;
}

std::vector<double> trapezoid_weights(const std::vector<double>& t) {
  const size_t n = t.size();
  std::vector<double> w(n, 0.0);
  if (n == 1) w[0] = 1;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double h = 0.5 * (t[i + 1] - t[i]);
    w[i] += h;
    w[i + 1] += h;
  }
  return w;
}

MaxDeviation max_abs_deviation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) throw Error("max_abs_deviation: series of different lengths or empty");
  MaxDeviation m;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = std::fabs(a[i] - b[i]);
    if (d > m.value || std::isnan(d)) {
      m.value = d;
      m.index = i;
      if (std::isnan(d)) break;
    }
  }
  return m;
}

double normalized_l2(const std::vector<double>& t, const std::vector<double>& a, const std::vector<double>& ref) {
  if (a.size() != ref.size() || t.size() != ref.size()) throw Error("normalized_l2: series of different lengths");
  const auto w = trapezoid_weights(t);
  double num = 0, den = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    num += w[i] * (a[i] - ref[i]) * (a[i] - ref[i]);
    den += w[i] * ref[i] * ref[i];
  }
  return den > 0 ? std::sqrt(num / den) : std::numeric_limits<double>::quiet_NaN();
}

Peak peak(const Series& s) {
  if (s.t.empty() || s.y.size() != s.t.size()) throw Error("peak: empty series");
  size_t k = 0;
  for (size_t i = 1; i < s.y.size(); ++i)
    if (s.y[i] > s.y[k]) k = i;
  return {s.t[k], s.y[k]};
}

}  // namespace cgdem::scaling
