// Welch spectral estimates of uniformly sampled signals (no I/O): power spectral density,
// cross-spectral density, magnitude-squared coherence, and the dominant peaks.
//
// Welch (1967), IEEE Trans. Audio Electroacoust. 15(2) 70-73. A signal x[0..N) sampled at
// fs = 1/dt is cut into K segments of L samples starting every S = L - overlap samples,
//   K = floor((N - L) / S) + 1                                                       (W1)
// Each segment is detrended (mean, or least-squares line, removed) to d_k[n] and windowed:
//   X_k(f_m) = sum_{n<L} w[n] d_k[n] exp(-2 pi i m n / L),  f_m = m fs / L, m = 0..L/2  (W2)
// (FFTW r2c, one plan per segment length, FFTW_ESTIMATE so that results are reproducible).
//
// Normalisation: the one-sided power spectral density, in signal units^2 / Hz (Pa^2/Hz),
//   P_xx(f_m) = c_m / (fs U K) sum_k |X_k(f_m)|^2,   U = sum_n w[n]^2,              (W3)
// c_m = 1 at m = 0 and at m = L/2 (L even), 2 elsewhere (the negative frequencies folded
// in). Dividing by U is the window power correction: by Parseval,
//   sum_m P_xx(f_m) df = (1/K) sum_k sum_n (w[n] d_k[n])^2 / U,   df = fs / L,       (W4)
// which for the rectangular window (U = L) is exactly the mean square of the detrended
// segments, and for any window is the signal variance in expectation for a stationary
// signal. So integrating P_xx over frequency gives the variance: white noise of variance
// sigma^2 reads a floor sigma^2 / (fs/2); a sine of amplitude A gives a peak whose band
// power (sum of P_xx df over the window's main lobe) is A^2/2 for any window.
// Amplitude-correct alternative (not what we write): the power spectrum
//   S_xx(f_m) = c_m / K sum_k |X_k(f_m)|^2 / (sum_n w[n])^2   in Pa^2,               (W5)
// where a sine of amplitude A centred on a bin reads A^2/2 at that bin for any window;
// S_xx = P_xx * ENBW with the equivalent noise bandwidth ENBW = fs U / (sum w)^2 Hz
// (fs/L for rect, 1.5 fs/L for Hann).
//
// Cross-spectral density P_xy as (W3) with conj(X_k) Y_k; magnitude-squared coherence
//   C_xy(f) = |P_xy(f)|^2 / (P_xx(f) P_yy(f))  in [0, 1]                             (W6)
// For independent signals its expectation is 1/K (non-overlapping segments; larger,
// 1/K_eff, when the segments overlap): the bias floor of a K-segment estimate.
#pragma once
#include <cmath>
#include <complex>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace cgdem::scaling {

enum class Window { hann, rect };
enum class Detrend { none, mean, linear };

Window parse_window(const std::string& name);    // "hann" | "rect"; Error naming --window
Detrend parse_detrend(const std::string& name);  // "none" | "mean" | "linear"; Error naming --detrend
std::string to_string(Window w);
std::string to_string(Detrend d);

// Periodic (DFT-even) window of length L: Hann w[n] = (1 - cos(2 pi n / L)) / 2, rect w = 1.
std::vector<double> window_coefficients(Window w, int L);

// Half-width, in bins, of the window's main lobe: the band that holds a sine's power.
int main_lobe_half_width(Window w);

// Window factors for the report: sum w, sum w^2, coherent gain (sum w)/L, power gain U/L,
// equivalent noise bandwidth in bins L U/(sum w)^2 and in Hz.
struct WindowFactors {
  double sum_w = 0, sum_w2 = 0, coherent_gain = 0, power_gain = 0, enbw_bins = 0, enbw_hz = 0;
};
WindowFactors window_factors(const std::vector<double>& w, double fs);

struct WelchParams {
  double fs = 0;      // sampling frequency, Hz (> 0)
  int segment = 0;    // L, samples per segment (>= 2)
  int overlap = 0;    // samples shared by consecutive segments, 0 <= overlap < L
  Window window = Window::hann;
  Detrend detrend = Detrend::mean;
};

// The estimator for one (fs, L, overlap, window, detrend): holds the window and the FFTW
// plan, so every signal of a study is transformed by the same plan. Not thread-safe.
class Welch {
 public:
  explicit Welch(const WelchParams& p);  // Error on fs <= 0, L < 2, overlap outside [0, L)
  ~Welch();
  Welch(const Welch&) = delete;
  Welch& operator=(const Welch&) = delete;

  const WelchParams& params() const { return p_; }
  const WindowFactors& factors() const { return factors_; }
  int bins() const { return p_.segment / 2 + 1; }
  double df() const { return p_.fs / p_.segment; }
  std::vector<double> frequencies() const;  // f_m = m df, m = 0..L/2
  int segments(size_t n) const;             // K of (W1); Error if n < L

  std::vector<double> psd(std::span<const double> x) const;  // (W3)
  std::vector<std::complex<double>> csd(std::span<const double> x, std::span<const double> y) const;

 private:
  // X_k of (W2) for the segment starting at `start`, into out_ (bins() values).
  const std::complex<double>* transform(std::span<const double> x, size_t start) const;

  struct Fft;
  WelchParams p_;
  std::vector<double> w_;
  WindowFactors factors_;
  std::unique_ptr<Fft> fft_;
};

// (W6) bin by bin; NaN where P_xx P_yy = 0 (coherence undefined).
std::vector<double> coherence(const std::vector<double>& pxx, const std::vector<double>& pyy,
                              const std::vector<std::complex<double>>& pxy);

// Integral of a one-sided density over all bins: sum_m P(f_m) df (the variance, (W4)).
double integrate(const std::vector<double>& psd, double df);

// Lowest bin at which a peak is sought (spectrum_significance.hpp, (S5)): bin 0 is the removed
// mean and bin 1 (f = 1/(L dt), the segment length) holds any trend or single pulse longer
// than half a segment, so never below bin kLowestPeakBin = 2; and a peak must stand above
// its left neighbour, which must lie outside the window's DC lobe (bins < h, h the main-lobe
// half-width: the per-segment mean removal lowers them, so any broadband transient shows a
// spurious rise from bin h - 1 to bin h). Hence the lowest peak bin max(2, h + 1): 3 for
// Hann, 2 for rect.
inline constexpr int kLowestPeakBin = 2;
int lowest_peak_bin(int half_width);
inline int lowest_peak_bin(Window w) { return lowest_peak_bin(main_lobe_half_width(w)); }

// Dominant frequencies: the local maxima of the PSD from bin lowest_peak_bin(h) on (P[k] > P[k-1],
// P[k] >= P[k+1]), largest first, at least 2 h + 1 bins apart, h the main-lobe half-width;
// with `level`, only those whose PSD exceeds level[k] (spectrum_significance.hpp). f_interp
// refines the bin by a parabola through log P at the three bins around the maximum (exact
// for a Gaussian lobe; within a tenth of a bin for Hann). band_power is sum P df over the
// bins within h of the maximum: A^2/2 for a sine of amplitude A.
struct Peak {
  int bin = 0;
  double f = 0, f_interp = 0, psd = 0, band_power = 0;
  // Against a background (spectrum_significance.hpp; NaN when none was given): the
  // background PSD and the significance level at the bin, and psd / level (> 1: significant).
  double background = NAN, level = NAN, ratio = NAN;
};
std::vector<Peak> find_peaks(const std::vector<double>& psd, double df, int half_width, int count,
                             const std::vector<double>* level = nullptr);

// Power in the band of bins k - half_width .. k + half_width (clipped to the spectrum):
// sum P df, the band_power of a peak at bin k.
double band_power(const std::vector<double>& psd, int k, int half_width, double df);

}  // namespace cgdem::scaling
