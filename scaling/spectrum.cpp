// Welch estimator on FFTW r2c plans; the equations (W1)-(W6) are in spectrum.hpp.
#include "scaling/spectrum.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace cgdem::scaling {
namespace {

// c_m * scale of (W3): 1 at DC and at the Nyquist bin (L even), 2 elsewhere.
template <class T>
void one_sided_scale(std::vector<T>& acc, int L, double scale) {
  const size_t last = acc.size() - 1;
  for (size_t m = 0; m < acc.size(); ++m) acc[m] *= (m == 0 || (L % 2 == 0 && m == last) ? 1.0 : 2.0) * scale;
}

}  // namespace

Window parse_window(const std::string& name) {
  if (name == "hann") return Window::hann;
  if (name == "rect") return Window::rect;
  throw Error(fmt::format("--window: unknown window '{}' (expected hann or rect)", name));
}

Detrend parse_detrend(const std::string& name) {
  if (name == "none") return Detrend::none;
  if (name == "mean") return Detrend::mean;
  if (name == "linear") return Detrend::linear;
  throw Error(fmt::format("--detrend: unknown detrending '{}' (expected none, mean or linear)", name));
}

std::string to_string(Window w) { return w == Window::hann ? "hann" : "rect"; }
std::string to_string(Detrend d) { return d == Detrend::none ? "none" : d == Detrend::mean ? "mean" : "linear"; }

std::vector<double> window_coefficients(Window w, int L) {
  std::vector<double> c(L, 1.0);
  if (w == Window::hann)
    for (int n = 0; n < L; ++n) c[n] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * n / L));
  return c;
}

int main_lobe_half_width(Window w) { return w == Window::hann ? 2 : 1; }

WindowFactors window_factors(const std::vector<double>& w, double fs) {
  WindowFactors f;
  for (double v : w) {
    f.sum_w += v;
    f.sum_w2 += v * v;
  }
  const double L = static_cast<double>(w.size());
  f.coherent_gain = f.sum_w / L;
  f.power_gain = f.sum_w2 / L;
  f.enbw_bins = L * f.sum_w2 / (f.sum_w * f.sum_w);
  f.enbw_hz = f.enbw_bins * fs / L;
  return f;
}

// One r2c plan of length L and its aligned buffers.
struct Welch::Fft {
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan plan = nullptr;
  explicit Fft(int L) {
    in = fftw_alloc_real(L);
    out = fftw_alloc_complex(L / 2 + 1);
    plan = fftw_plan_dft_r2c_1d(L, in, out, FFTW_ESTIMATE);
    if (!in || !out || !plan) throw Error(fmt::format("FFTW: cannot plan a real transform of {} samples", L));
  }
  ~Fft() {
    if (plan) fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
  }
};

Welch::Welch(const WelchParams& p) : p_(p) {
  if (!(p.fs > 0) || !std::isfinite(p.fs)) throw Error(fmt::format("spectrum: sampling frequency {} Hz is not positive", p.fs));
  if (p.segment < 2) throw Error(fmt::format("--segment: {} samples, at least 2 needed", p.segment));
  if (p.overlap < 0 || p.overlap >= p.segment)
    throw Error(fmt::format("--overlap: {} samples of a {}-sample segment (expected 0 <= overlap < segment)", p.overlap,
                            p.segment));
  w_ = window_coefficients(p.window, p.segment);
  factors_ = window_factors(w_, p.fs);
  fft_ = std::make_unique<Fft>(p.segment);
}

Welch::~Welch() = default;

std::vector<double> Welch::frequencies() const {
  std::vector<double> f(bins());
  for (int m = 0; m < bins(); ++m) f[m] = m * df();
  return f;
}

int Welch::segments(size_t n) const {
  const size_t L = p_.segment, S = p_.segment - p_.overlap;
  if (n < L)
    throw Error(fmt::format("spectrum: {} samples are fewer than one segment of {} (shorten --segment or widen --from/--to)",
                            n, L));
  return static_cast<int>((n - L) / S + 1);  // (W1)
}

const std::complex<double>* Welch::transform(std::span<const double> x, size_t start) const {
  const int L = p_.segment;
  const double* seg = x.data() + start;
  // Detrend: d = x - (a + b (n - c)), least squares, c the segment's centre.
  double a = 0, b = 0;
  if (p_.detrend != Detrend::none) {
    for (int n = 0; n < L; ++n) a += seg[n];
    a /= L;
  }
  const double c = 0.5 * (L - 1);
  if (p_.detrend == Detrend::linear) {
    double sxy = 0, sxx = 0;
    for (int n = 0; n < L; ++n) {
      sxy += (n - c) * (seg[n] - a);
      sxx += (n - c) * (n - c);
    }
    b = sxy / sxx;
  }
  for (int n = 0; n < L; ++n) fft_->in[n] = w_[n] * (seg[n] - a - b * (n - c));
  fftw_execute(fft_->plan);  // (W2)
  return reinterpret_cast<const std::complex<double>*>(fft_->out);
}

std::vector<std::complex<double>> Welch::csd(std::span<const double> x, std::span<const double> y) const {
  if (x.size() != y.size()) throw Error("spectrum: cross-spectrum of signals of different lengths");
  const int K = segments(x.size());
  const size_t S = p_.segment - p_.overlap;
  std::vector<std::complex<double>> Xk(bins()), acc(bins());
  for (int k = 0; k < K; ++k) {
    const std::complex<double>* X = transform(x, k * S);
    std::copy(X, X + bins(), Xk.begin());
    const std::complex<double>* Y = transform(y, k * S);  // overwrites the buffer X pointed to
    for (int m = 0; m < bins(); ++m) acc[m] += std::conj(Xk[m]) * Y[m];
  }
  one_sided_scale(acc, p_.segment, 1.0 / (p_.fs * factors_.sum_w2 * K));  // (W3)
  return acc;
}

std::vector<double> Welch::psd(std::span<const double> x) const {
  const int K = segments(x.size());
  const size_t S = p_.segment - p_.overlap;
  std::vector<double> acc(bins(), 0.0);
  for (int k = 0; k < K; ++k) {
    const std::complex<double>* X = transform(x, k * S);
    for (int m = 0; m < bins(); ++m) acc[m] += std::norm(X[m]);
  }
  one_sided_scale(acc, p_.segment, 1.0 / (p_.fs * factors_.sum_w2 * K));  // (W3)
  return acc;
}

std::vector<double> coherence(const std::vector<double>& pxx, const std::vector<double>& pyy,
                              const std::vector<std::complex<double>>& pxy) {
  std::vector<double> c(pxy.size());
  for (size_t m = 0; m < c.size(); ++m) {
    const double d = pxx[m] * pyy[m];
    c[m] = d > 0 ? std::norm(pxy[m]) / d : std::nan("");  // (W6)
  }
  return c;
}

double integrate(const std::vector<double>& psd, double df) {
  double s = 0;
  for (double v : psd) s += v;
  return s * df;
}

int lowest_peak_bin(int half_width) { return std::max(kLowestPeakBin, half_width + 1); }

std::vector<Peak> find_peaks(const std::vector<double>& psd, double df, int half_width, int count,
                             const std::vector<double>* level) {
  const int n = static_cast<int>(psd.size());
  std::vector<int> maxima;
  for (int k = lowest_peak_bin(half_width); k < n; ++k)
    if (psd[k] > psd[k - 1] && (k == n - 1 || psd[k] >= psd[k + 1]) && (!level || psd[k] > (*level)[k]))
      maxima.push_back(k);
  std::stable_sort(maxima.begin(), maxima.end(), [&](int a, int b) { return psd[a] > psd[b]; });
  std::vector<Peak> peaks;
  for (int k : maxima) {
    if (static_cast<int>(peaks.size()) >= count) break;
    if (std::any_of(peaks.begin(), peaks.end(), [&](const Peak& p) { return std::abs(p.bin - k) <= 2 * half_width; }))
      continue;
    Peak p;
    p.bin = k;
    p.f = p.f_interp = k * df;
    p.psd = psd[k];
    if (k + 1 < n && psd[k - 1] > 0 && psd[k + 1] > 0 && psd[k] > 0) {
      const double a = std::log(psd[k - 1]), b = std::log(psd[k]), c = std::log(psd[k + 1]);
      const double den = a - 2 * b + c;
      if (den < 0) p.f_interp = (k + 0.5 * (a - c) / den) * df;
    }
    p.band_power = band_power(psd, k, half_width, df);
    if (level) p.level = (*level)[k], p.ratio = psd[k] / (*level)[k];
    peaks.push_back(p);
  }
  return peaks;
}

double band_power(const std::vector<double>& psd, int k, int half_width, double df) {
  const int n = static_cast<int>(psd.size());
  double sum = 0;
  for (int j = std::max(0, k - half_width); j <= std::min(n - 1, k + half_width); ++j) sum += psd[j] * df;
  return sum;
}

}  // namespace cgdem::scaling
