// Significance of spectral peaks against a red-noise (AR(1)) background (no I/O).
//
// A die-filling pressure is a transient: a smooth pulse puts almost all its variance into
// the lowest bins, and the largest local maximum of its PSD is then the segment length
// (f_1 = 1/(L dt)), not an oscillation. A peak is therefore reported only when it stands
// above what a first-order autoregressive process of the same variance and lag-1
// correlation would give at that frequency, at a stated confidence, and only from the
// lowest resolvable frequency on. The method, after Gilman, Fuglister & Mitchell (1963),
// J. Atmos. Sci. 20, 182-184, Torrence & Compo (1998), Bull. Amer. Meteor. Soc. 79, 61-78
// (their section 4), and Schulz & Mudelsee (2002), Comput. Geosci. 28, 421-426 (REDFIT):
//
// (S1) Background model. x_t = phi x_{t-1} + e_t, e white with variance s_e^2, has the
//      variance s^2 = s_e^2 / (1 - phi^2) and the one-sided density (integral over
//      0..fs/2 equal to s^2)
//        G(f) = (2 s^2 / fs) (1 - phi^2) / (1 - 2 phi cos(2 pi f / fs) + phi^2).
// (S2) Fit. The series is detrended as a whole (its mean, or its least-squares line with
//      --detrend linear) to d_t, t < N; s^2 = (1/N) sum d_t^2; the lag-1 autocorrelation
//        r1 = sum_{t<N-1} d_t d_{t+1} / sum_t d_t^2,
//      and, as the sample r1 of a mean-removed series is biased low by about
//      (1 + 4 phi) / N (Kendall 1954, Marriott & Pope 1954),
//        phi = (N r1 + 1) / (N - 4),  clipped to [-0.999, 0.999];
//      its standard error is sqrt((1 - phi^2) / N) (Bartlett).
// (S3) Distribution of the estimate. Under the background, a Welch estimate at a bin is
//      G(f) chi^2_nu / nu with nu the equivalent degrees of freedom of K overlapping
//      windowed segments (Welch 1967; Percival & Walden 1993, eq. 292b):
//        nu = 2K / (1 + 2 sum_{j=1}^{K-1} (1 - j/K) rho(jS)^2),
//        rho(s) = sum_{n<L-s} w[n] w[n+s] / sum_n w[n]^2,
//      S = L - overlap the segment step (nu = 2K without overlap; 2K / (1 + (1/18)(1 - 1/K))
//      for Hann at 50 %, where rho(L/2) = 1/6). The DC and Nyquist bins, real-valued, have nu/2.
// (S4) Level. The c-level (c = 0.95 by default) at bin m is
//        G(f_m) Q_nu(c) / nu,   Q_nu the chi-square quantile,
//      This level is pointwise: in pure background a fraction 1 - c of the bins exceeds it,
//      so over the M bins searched a red-noise spectrum shows (1 - c) M exceedances and
//      almost always at least one (M = 125: 399 of 400 series in the test). A peak is
//      therefore reported against the global level, the pointwise level at the per-bin
//      confidence c^(1/M) (Sidak 1967), so that pure background shows no peak at all in a
//      fraction c of the series (conservative: neighbouring bins are correlated and only
//      local maxima count). `cgdem spectrum --pointwise` uses the pointwise level instead.
// (S5) Lowest resolvable frequency. Bin 0 is the (removed) mean, bin 1 (f = 1/(L dt)) holds
//      whatever varies over a segment length, a trend or a single pulse; neither can be an
//      oscillation resolved by the segment: peaks have periods of at most half a segment
//      (bin >= 2). A peak must also rise above its left neighbour, and the bins of the
//      window's DC lobe (k < h, h the main-lobe half-width) are lowered by the per-segment
//      mean removal, so that any broadband transient rises from bin h - 1 to bin h: the
//      lowest peak bin is max(2, h + 1), bin 3 for Hann, 2 for rect (lowest_peak_bin,
//      spectrum.hpp). Without this, a 2 ms Gaussian pulse in a 51 ms Hann segment reads as
//      a significant "peak" at bin 2 (tests/scaling/spectrum_significance_test.cpp).
//
// The chi-square quantile is computed here from the regularized incomplete gamma function
// (series and continued fraction), inverted by bisection.
#pragma once
#include <span>
#include <vector>

#include "scaling/spectrum.hpp"

namespace cgdem::scaling {

// lowest_peak_bin (S5) is defined in spectrum.hpp, with find_peaks.

// Regularized lower incomplete gamma function P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0.
double regularized_gamma_p(double a, double x);
// Chi-square distribution with nu (> 0, not necessarily whole) degrees of freedom.
double chi2_cdf(double x, double nu);
// x with chi2_cdf(x, nu) = p, 0 < p < 1 (relative accuracy ~1e-12). Error on bad arguments.
double chi2_quantile(double p, double nu);

struct Ar1Fit {
  double phi = 0;       // (S2), bias-corrected and clipped
  double r1 = 0;        // the raw lag-1 autocorrelation
  double variance = 0;  // s^2 of the detrended series
  double phi_se = 0;    // sqrt((1 - phi^2) / N)
  size_t n = 0;
};
// (S2). Detrend::none is treated as mean removal (an autocorrelation needs a zero mean).
// Error on fewer than 8 samples.
Ar1Fit fit_ar1(std::span<const double> x, Detrend d);

// (S1) at the frequencies f (Hz), sampling frequency fs.
std::vector<double> ar1_spectrum(const Ar1Fit& a, const std::vector<double>& f, double fs);

// (S3): nu for K segments of the window w (length L) starting every L - overlap samples.
double welch_dof(const std::vector<double>& w, int overlap, int segments);

// (S4): the per-bin confidence that makes `confidence` the chance that none of `bins`
// independent bins of pure background exceeds its level: confidence^(1/bins).
double global_confidence(double confidence, int bins);

// (S4): the c-level of a background G on the bins 0..L/2 of an L-sample segment (nu/2 at
// DC and, for even L, at the Nyquist bin).
std::vector<double> significance_level(const std::vector<double>& background, double nu, double confidence, int L);

// The significant peaks: local maxima of the PSD at bins >= lowest_peak_bin(h) (P[k] > P[k-1],
// P[k] >= P[k+1]) whose PSD exceeds `level`, largest PSD first, at least 2h + 1 bins apart
// (h the main-lobe half-width), at most `count`. Peak::background, level and ratio are
// filled in. `largest` (optional) receives the largest local maximum from that bin on,
// significant or not (bin -1 when there is none).
std::vector<Peak> significant_peaks(const std::vector<double>& psd, const std::vector<double>& background,
                                    const std::vector<double>& level, double df, int half_width, int count,
                                    Peak* largest = nullptr);

}  // namespace cgdem::scaling
