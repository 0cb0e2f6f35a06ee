// Red-noise background and chi-square levels; equations (S1)-(S5) in spectrum_significance.hpp.
#include "scaling/spectrum_significance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"

namespace cgdem::scaling {
namespace {

// x^a e^-x / Gamma(a), the common factor of the series and the continued fraction.
double gamma_prefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

// P(a, x) by its power series: x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)); for x < a + 1.
double gamma_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 10000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < 1e-16 * std::fabs(sum)) break;
  }
  return sum * gamma_prefactor(a, x);
}

// Q(a, x) = 1 - P(a, x) by its continued fraction
//   Q = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - 2 (2 - a) / (x + 5 - a - ...)))
// evaluated from the front (modified Lentz); for x >= a + 1, where it converges fast.
double gamma_q_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1 / d;
    const double step = d * c;
    h *= step;
    if (std::fabs(step - 1) < 1e-16) break;
  }
  return h * gamma_prefactor(a, x);
}

}  // namespace

double regularized_gamma_p(double a, double x) {
  if (!(a > 0) || !(x >= 0)) throw Error(fmt::format("incomplete gamma P(a = {}, x = {}): needs a > 0, x >= 0", a, x));
  if (x == 0) return 0;
  if (std::isinf(x)) return 1;
  return x < a + 1 ? gamma_p_series(a, x) : 1 - gamma_q_fraction(a, x);
}

double chi2_cdf(double x, double nu) { return x <= 0 ? 0.0 : regularized_gamma_p(0.5 * nu, 0.5 * x); }

double chi2_quantile(double p, double nu) {
  if (!(p > 0 && p < 1) || !(nu > 0) || !std::isfinite(nu))
    throw Error(fmt::format("chi-square quantile: probability {} must lie in (0, 1) and nu = {} be positive", p, nu));
  double lo = 0, hi = std::max(1.0, nu);
  while (chi2_cdf(hi, nu) < p) lo = hi, hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (chi2_cdf(mid, nu) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Ar1Fit fit_ar1(std::span<const double> x, Detrend detrend) {
  const size_t N = x.size();
  if (N < 8) throw Error(fmt::format("red-noise fit: {} samples, at least 8 needed", N));
  // Whole-series detrending (S2): mean, or the least-squares line about the centre.
  double a = 0, b = 0;
  for (double v : x) a += v;
  a /= N;
  const double c = 0.5 * (N - 1.0);
  if (detrend == Detrend::linear) {
    double sxy = 0, sxx = 0;
    for (size_t t = 0; t < N; ++t) sxy += (t - c) * (x[t] - a), sxx += (t - c) * (t - c);
    b = sxy / sxx;
  }
  std::vector<double> d(N);
  for (size_t t = 0; t < N; ++t) d[t] = x[t] - a - b * (t - c);
  double s0 = 0, s1 = 0;
  for (size_t t = 0; t < N; ++t) s0 += d[t] * d[t];
  for (size_t t = 0; t + 1 < N; ++t) s1 += d[t] * d[t + 1];
  Ar1Fit f;
  f.n = N;
  f.variance = s0 / N;
  f.r1 = s0 > 0 ? s1 / s0 : 0.0;
  f.phi = std::clamp((N * f.r1 + 1.0) / (N - 4.0), -0.999, 0.999);  // bias correction (S2)
  f.phi_se = std::sqrt((1 - f.phi * f.phi) / N);
  return f;
}

std::vector<double> ar1_spectrum(const Ar1Fit& a, const std::vector<double>& f, double fs) {
  std::vector<double> g(f.size());
  const double phi = a.phi;
  for (size_t m = 0; m < f.size(); ++m)  // (S1)
    g[m] = 2 * a.variance / fs * (1 - phi * phi) /
           (1 - 2 * phi * std::cos(2 * std::numbers::pi * f[m] / fs) + phi * phi);
  return g;
}

double welch_dof(const std::vector<double>& w, int overlap, int segments) {
  const int L = static_cast<int>(w.size()), S = L - overlap, K = segments;
  double U = 0;
  for (double v : w) U += v * v;
  double sum = 0;
  for (int j = 1; j < K && j * S < L; ++j) {  // rho(jS) = 0 once the segments no longer overlap
    const int s = j * S;
    double r = 0;
    for (int n = 0; n + s < L; ++n) r += w[n] * w[n + s];
    r /= U;
    sum += (1.0 - static_cast<double>(j) / K) * r * r;
  }
  return 2.0 * K / (1 + 2 * sum);  // (S3)
}

double global_confidence(double confidence, int bins) { return std::pow(confidence, 1.0 / std::max(1, bins)); }

std::vector<double> significance_level(const std::vector<double>& background, double nu, double confidence, int L) {
  const double full = chi2_quantile(confidence, nu) / nu, half = chi2_quantile(confidence, 0.5 * nu) / (0.5 * nu);
  std::vector<double> level(background.size());
  const size_t last = background.size() - 1;
  for (size_t m = 0; m < level.size(); ++m)  // (S4)
    level[m] = background[m] * (m == 0 || (L % 2 == 0 && m == last) ? half : full);
  return level;
}

std::vector<Peak> significant_peaks(const std::vector<double>& psd, const std::vector<double>& background,
                                    const std::vector<double>& level, double df, int half_width, int count,
                                    Peak* largest) {
  std::vector<Peak> peaks = find_peaks(psd, df, half_width, count, &level);
  for (Peak& p : peaks) p.background = background[p.bin];
  if (largest) {
    const std::vector<Peak> any = find_peaks(psd, df, half_width, 1);
    *largest = any.empty() ? Peak{-1} : any[0];
    if (!any.empty()) {
      largest->background = background[largest->bin];
      largest->level = level[largest->bin];
      largest->ratio = largest->psd / largest->level;
    }
  }
  return peaks;
}

}  // namespace cgdem::scaling
