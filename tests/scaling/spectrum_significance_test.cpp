// Peaks against red noise (scaling/spectrum_significance.hpp) on synthetic signals:
//   * the chi-square quantile against tabulated values, and the Welch degrees of freedom
//     against their closed forms and against the scatter of white-noise estimates;
//   * the AR(1) fit recovers a known phi within its standard error;
//   * a sine in red noise is found at its frequency (within one bin) and is significant;
//   * a single Gaussian pulse in red noise gives no significant peak (the Case 1-3 shape);
//   * pure AR(1) noise exceeds the 95 % level in about 5 % of the bins over many seeds.
// Every test prints its figures; the tolerances are stated at each check.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "scaling/spectrum.hpp"
#include "scaling/spectrum_report.hpp"
#include "scaling/spectrum_significance.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem::scaling {
namespace {

// x_t = phi x_{t-1} + e_t, e ~ N(0, sigma_e^2), started from the stationary distribution.
std::vector<double> ar1_noise(size_t n, double phi, double sigma_e, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> e(0.0, sigma_e);
  std::vector<double> x(n);
  x[0] = e(rng) / std::sqrt(1 - phi * phi);
  for (size_t t = 1; t < n; ++t) x[t] = phi * x[t - 1] + e(rng);
  return x;
}

struct Analysis {
  std::vector<double> psd, background, level, pointwise;
  std::vector<Peak> peaks;
  Peak largest;
  Ar1Fit fit;
  double nu = 0;
};

// One series through the estimator and the test, as analyse_series does it: peaks against
// the global level (every searched bin at confidence^(1/M)); `pointwise` keeps the level at
// `confidence` for each bin.
Analysis analyse(const std::vector<double>& x, const WelchParams& p, double confidence = 0.95, int count = 3) {
  const Welch welch(p);
  Analysis a;
  a.psd = welch.psd(x);
  a.fit = fit_ar1(x, p.detrend);
  a.background = ar1_spectrum(a.fit, welch.frequencies(), p.fs);
  a.nu = welch_dof(window_coefficients(p.window, p.segment), p.overlap, welch.segments(x.size()));
  const int M = welch.bins() - lowest_peak_bin(p.window);
  a.pointwise = significance_level(a.background, a.nu, confidence, p.segment);
  a.level = significance_level(a.background, a.nu, global_confidence(confidence, M), p.segment);
  a.peaks = significant_peaks(a.psd, a.background, a.level, welch.df(), main_lobe_half_width(p.window), count,
                              &a.largest);
  return a;
}

TEST(ChiSquare, QuantilesMatchTables) {
  struct Row {
    double p, nu, want;
  };
  // Tabulated quantiles (e.g. Abramowitz & Stegun table 26.8); nu = 2 is -2 ln(1 - p) exactly.
  const Row rows[] = {{0.95, 1, 3.841458820694124}, {0.95, 2, -2 * std::log(0.05)}, {0.95, 10, 18.307038053275146},
                      {0.95, 100, 124.34211340400407}, {0.05, 10, 3.940299136119}, {0.99, 5, 15.086272469388991},
                      {0.5, 1, 0.454936423119572}};
  double worst = 0;
  for (const Row& r : rows) {
    const double got = chi2_quantile(r.p, r.nu), rel = std::fabs(got - r.want) / r.want;
    std::printf("chi2 quantile p = %.2f nu = %g: %.12g (table %.12g, relative error %.2e)\n", r.p, r.nu, got, r.want,
                rel);
    worst = std::max(worst, rel);
  }
  EXPECT_LT(worst, 1e-9);
  // Non-integer nu: the quantile inverts the distribution function.
  for (double nu : {0.7, 2.5, 51.3, 400.0}) {
    const double x = chi2_quantile(0.95, nu), back = chi2_cdf(x, nu);
    std::printf("nu = %g: Q(0.95) = %.10g, cdf(Q) - 0.95 = %.2e\n", nu, x, back - 0.95);
    EXPECT_NEAR(back, 0.95, 1e-12);
  }
}

TEST(WelchDof, ClosedFormsAndTheScatterOfWhiteNoise) {
  // Without overlap nu = 2K; Hann at 50 %: rho(L/2) = sum_{n<L/2} w[n] w[n+L/2] / U = (L/16) / (3L/8) = 1/6,
  // nu = 2K / (1 + 2/36 (1 - 1/K)).
  const int L = 64, K = 31;
  const double rect = welch_dof(window_coefficients(Window::rect, L), 0, K);
  const double hann = welch_dof(window_coefficients(Window::hann, L), L / 2, K);
  const double hann_want = 2.0 * K / (1 + 2.0 / 36 * (1 - 1.0 / K));
  std::printf("nu: rect no overlap %.6f (want %d), Hann 50 %% %.6f (want %.6f)\n", rect, 2 * K, hann, hann_want);
  EXPECT_NEAR(rect, 2.0 * K, 1e-12);
  EXPECT_NEAR(hann, hann_want, 1e-9);
  // White noise: the estimate at a bin is sigma^2/(fs/2) chi^2_nu / nu, so var / mean^2 = 2 / nu.
  const WelchParams p{1.0, L, L / 2, Window::hann, Detrend::mean};
  const Welch welch(p);
  double s1 = 0, s2 = 0;
  long n = 0;
  for (uint64_t seed = 1; seed <= 200; ++seed) {
    const std::vector<double> x = ar1_noise(L / 2 * (K + 1), 0.0, 1.0, seed);
    const std::vector<double> P = welch.psd(x);
    for (int m = 2; m < L / 2; ++m) s1 += P[m], s2 += P[m] * P[m], ++n;
  }
  const double mean = s1 / n, ratio = (s2 / n - mean * mean) / (mean * mean);
  std::printf("white noise, Hann 50 %%, K = %d: var/mean^2 = %.5f, 2/nu = %.5f (%+.1f %%), %ld estimates\n", K, ratio,
              2 / hann, 100 * (ratio * hann / 2 - 1), n);
  EXPECT_NEAR(ratio * hann / 2, 1.0, 0.08);  // 6000 correlated estimates: a few % of scatter
}

TEST(Ar1Fit, RecoversPhiWithinItsStandardError) {
  // Per phi: 200 series of 2048 samples; the estimates scatter by their standard error
  // sqrt((1 - phi^2)/N) around phi (bias corrected): the mean within 3 standard errors of
  // the mean, the rms of (phi_hat - phi)/se within 15 % of 1, about 68 % within one se.
  for (double phi : {0.3, 0.7, 0.9}) {
    const int M = 200;
    const size_t N = 2048;
    double sum = 0, sum_z2 = 0, se = 0;
    int inside = 0;
    for (int s = 0; s < M; ++s) {
      const Ar1Fit f = fit_ar1(ar1_noise(N, phi, 1.0, 1000 + s), Detrend::mean);
      const double z = (f.phi - phi) / f.phi_se;
      sum += f.phi, sum_z2 += z * z, se = f.phi_se;
      inside += std::fabs(z) <= 1;
    }
    const double mean = sum / M, rms_z = std::sqrt(sum_z2 / M), within = double(inside) / M;
    std::printf("phi = %.1f: mean estimate %.5f (se %.5f, of the mean %.5f), rms (phi_hat - phi)/se %.3f, "
                "%.1f %% within one se\n",
                phi, mean, se, se / std::sqrt(M), rms_z, 100 * within);
    EXPECT_NEAR(mean, phi, 3 * se / std::sqrt(M));
    EXPECT_NEAR(rms_z, 1.0, 0.15);
    EXPECT_NEAR(within, 0.68, 0.10);
  }
  // One long series: within one standard error.
  const Ar1Fit f = fit_ar1(ar1_noise(1 << 16, 0.8, 1.0, 7), Detrend::linear);
  std::printf("phi = 0.8, N = 65536: %.5f +- %.5f (error %.2f se); variance %.4f (theory %.4f)\n", f.phi, f.phi_se,
              (f.phi - 0.8) / f.phi_se, f.variance, 1 / (1 - 0.64));
  EXPECT_LT(std::fabs(f.phi - 0.8), f.phi_se);
  EXPECT_NEAR(f.variance, 1 / (1 - 0.64), 0.05 * 1 / (1 - 0.64));
}

TEST(RedNoiseTest, SineInRedNoiseIsFoundAndSignificant) {
  // fs = 1 kHz, 8192 samples, L = 512 (df = 1.953 Hz, K = 31), phi = 0.7, sigma_e = 1;
  // a sine of amplitude 0.5 at 123.4 Hz: its peak bin stands ~5x above the 95 % level.
  const double fs = 1000, f0 = 123.4, A = 0.5;
  const WelchParams p{fs, 512, 256, Window::hann, Detrend::mean};
  const double df = fs / p.segment;
  double worst_offset = 0, lowest_ratio = INFINITY;
  int found = 0;
  const int M = 20;
  for (int s = 0; s < M; ++s) {
    std::vector<double> x = ar1_noise(8192, 0.7, 1.0, 50 + s);
    for (size_t t = 0; t < x.size(); ++t) x[t] += A * std::sin(2 * std::numbers::pi * f0 * t / fs + 0.3 * s);
    const Analysis a = analyse(x, p);
    if (a.peaks.empty()) continue;
    ++found;
    worst_offset = std::max(worst_offset, std::fabs(a.peaks[0].f_interp - f0) / df);
    lowest_ratio = std::min(lowest_ratio, a.peaks[0].ratio);
    if (s == 0)
      std::printf("seed 0: phi %.4f, nu %.2f, dominant %.3f Hz (interpolated %.3f, f0 %.3f), PSD %.4g = %.2f x the "
                  "level, %zu significant peak(s)\n",
                  a.fit.phi, a.nu, a.peaks[0].f, a.peaks[0].f_interp, f0, a.peaks[0].psd, a.peaks[0].ratio,
                  a.peaks.size());
  }
  std::printf("sine in red noise: found in %d of %d series; worst offset %.3f bin; lowest ratio to the level %.2f\n",
              found, M, worst_offset, lowest_ratio);
  EXPECT_EQ(found, M);
  EXPECT_LE(worst_offset, 1.0);  // within one bin
  EXPECT_GT(lowest_ratio, 1.0);
}

// A pulse p(t) = H exp(-(t - tc)^2 / (2 w^2)) (H = 15 Pa, tc = 0.16 s) on red noise (phi 0.9),
// sampled like a Case 1-3 cell pressure: 0.3 s at 0.1 ms (3001 samples), the automatic
// segment L = 512 (df = 19.5 Hz), pulse widths w from 20 ms (the die pressure's event) to
// 1 ms (a start-up spike).
std::vector<double> pulse_in_noise(double H, double w, uint64_t seed, double sigma_e = 0.05) {
  const double dt = 1e-4, tc = 0.16;
  std::vector<double> x = ar1_noise(3001, 0.9, sigma_e, seed);
  for (size_t t = 0; t < x.size(); ++t) x[t] += H * std::exp(-0.5 * std::pow((t * dt - tc) / w, 2));
  return x;
}

TEST(RedNoiseTest, GaussianPulseInRedNoiseHasNoSignificantPeak) {
  const WelchParams p{1e4, 512, 256, Window::hann, Detrend::mean};
  const int M = 50;
  for (double sigma_e : {0.05, 0.5})
  for (double w : {0.02, 0.005, 0.002, 0.001}) {  // pulse widths, s
    int with_peak = 0;
    double worst_ratio = 0, largest_f = 0;
    for (int s = 0; s < M; ++s) {
      const Analysis a = analyse(pulse_in_noise(15.0, w, 300 + s, sigma_e), p);
      with_peak += !a.peaks.empty();
      if (s == 0 && !a.peaks.empty())
        std::printf("  seed 0: first significant peak %.4g Hz (bin %d), PSD %.4g, background %.4g, %.3f x the level\n",
                    a.peaks[0].f, a.peaks[0].bin, a.peaks[0].psd, a.peaks[0].background, a.peaks[0].ratio);
      if (a.largest.bin >= 0 && a.largest.ratio > worst_ratio) worst_ratio = a.largest.ratio, largest_f = a.largest.f;
      if (s == 0)
        std::printf("pulse w = %g s, seed 0: phi %.4f (r1 %.4f), variance %.4g Pa^2, nu %.2f; largest local maximum "
                    "from bin 2: %.4g Hz at %.3f of the level\n",
                    w, a.fit.phi, a.fit.r1, a.fit.variance, a.nu, a.largest.f, a.largest.ratio);
    }
    std::printf("pulse w = %g s, noise sigma_e = %g: %d of %d series with a significant peak; largest local maximum "
                "at %.3f of the level (at %.4g Hz)\n",
                w, sigma_e, with_peak, M, worst_ratio, largest_f);
    // The pulse dominating the variance (as in Case 1-3): no peak in any series. With noise
    // of a variance a tenth of the pulse's (sigma_e = 0.5) the fitted phi (0.95-0.995, the
    // pulse's) is redder than the noise's 0.9, the background falls below the noise floor
    // at high frequencies and noise maxima there pass the global level in 4-49 of the 50
    // series (printed above; docs/spectra.md, "Limits"): a single AR(1) is not a model of
    // a transient plus noise.
    if (sigma_e < 0.1) EXPECT_EQ(with_peak, 0);
  }
  // The same through analyse_series: the summary says so, and no "dominant" line at bin 1.
  PressureSeries ser;
  ser.source = "synthetic";
  for (int t = 0; t <= 3000; ++t) ser.t.push_back(t * 1e-4);
  ser.cells = {"B"};
  ser.p = {pulse_in_noise(15.0, 0.02, 1)};
  const SpectrumAnalysis a = analyse_series({ser}, {"pulse"}, SpectrumSettings{});
  const std::string summary = dominant_summary(a);
  std::printf("%s", summary.c_str());
  EXPECT_EQ(a.params.segment, 512);
  EXPECT_NE(summary.find("B: no significant peak"), std::string::npos);
  EXPECT_EQ(summary.find("dominant"), std::string::npos);
}

TEST(RedNoiseTest, PureAr1NoiseExceedsTheLevelAtTheNominalRate) {
  // 400 series of 4096 samples, phi = 0.7, L = 256 (K = 31, Hann 50 %).
  // Pointwise level: the fraction of the searched bins (3 .. L/2) whose estimate exceeds the
  // 95 % level; nominal 5 %, tolerance 4-6 % (the binomial scatter of 50,000 correlated
  // tests is ~0.2 %; the fitted phi and the chi-square approximation of overlapping segments
  // add a few tenths of a per cent).
  // Global level: the fraction of the series that report any significant peak; nominal at
  // most 5 % (Sidak over M bins is conservative for correlated bins and local maxima),
  // tolerance 1-6 %.
  const WelchParams p{1.0, 256, 128, Window::hann, Detrend::mean};
  long tested = 0, above = 0, maxima = 0, significant_maxima = 0;
  int series_with_peak = 0, series_pointwise = 0;
  const int M = 400;
  for (int s = 0; s < M; ++s) {
    const Analysis a = analyse(ar1_noise(4096, 0.7, 1.0, 5000 + s), p);
    bool any = false;
    for (int m = lowest_peak_bin(p.window); m <= p.segment / 2; ++m) {
      ++tested;
      above += a.psd[m] > a.pointwise[m];
      if (a.psd[m] > a.psd[m - 1] && (m == p.segment / 2 || a.psd[m] >= a.psd[m + 1])) {
        ++maxima;
        significant_maxima += a.psd[m] > a.pointwise[m];
        any = any || a.psd[m] > a.pointwise[m];
      }
    }
    series_pointwise += any;
    series_with_peak += !a.peaks.empty();
  }
  const double rate = double(above) / tested, series_rate = double(series_with_peak) / M;
  std::printf("pure AR(1), phi = 0.7, pointwise 95 %% level: %.2f %% of %ld bins above it (nominal 5 %%), %.2f %% of "
              "%ld local maxima, %d of %d series with a local maximum above it\n",
              100 * rate, tested, 100.0 * significant_maxima / maxima, maxima, series_pointwise, M);
  std::printf("pure AR(1), phi = 0.7, global 95 %% level (%d bins): %d of %d series = %.2f %% report a significant "
              "peak (nominal at most 5 %%)\n",
              p.segment / 2 + 1 - lowest_peak_bin(p.window), series_with_peak, M, 100 * series_rate);
  EXPECT_NEAR(rate, 0.05, 0.01);
  EXPECT_GE(series_rate, 0.01);
  EXPECT_LE(series_rate, 0.06);
  // The pointwise 99 % level: 1 % nominal, tolerance 0.5-1.5 %.
  long above99 = 0;
  tested = 0;
  for (int s = 0; s < M; ++s) {
    const Analysis a = analyse(ar1_noise(4096, 0.7, 1.0, 9000 + s), p, 0.99);
    for (int m = lowest_peak_bin(p.window); m <= p.segment / 2; ++m) ++tested, above99 += a.psd[m] > a.pointwise[m];
  }
  std::printf("pure AR(1), phi = 0.7: %.2f %% of the bins above the pointwise 99 %% level (nominal 1 %%)\n",
              100.0 * above99 / tested);
  EXPECT_NEAR(double(above99) / tested, 0.01, 0.005);
}

TEST(RedNoiseTest, NoPeakBelowTheLowestResolvableFrequency) {
  // A strong sine at bin 1 (f = df) and a weaker one at bin 6: only the second is a peak.
  const double fs = 1000;
  const WelchParams p{fs, 128, 64, Window::hann, Detrend::mean};
  std::vector<double> x = ar1_noise(2048, 0.5, 0.1, 3);
  for (size_t t = 0; t < x.size(); ++t)
    x[t] += 5 * std::sin(2 * std::numbers::pi * (fs / 128) * t / fs) + std::sin(2 * std::numbers::pi * 6 * (fs / 128) * t / fs);
  const Analysis a = analyse(x, p);
  std::printf("sines at bins 1 and 6: %zu significant peak(s), the first at bin %d (%.4g x the level)\n",
              a.peaks.size(), a.peaks.empty() ? -1 : a.peaks[0].bin, a.peaks.empty() ? NAN : a.peaks[0].ratio);
  ASSERT_FALSE(a.peaks.empty());
  EXPECT_EQ(a.peaks[0].bin, 6);
  for (const Peak& pk : a.peaks) EXPECT_GE(pk.bin, lowest_peak_bin(2));
}

TEST(RedNoiseTest, BadArgumentsAreClearErrors) {
  EXPECT_THROW(chi2_quantile(1.0, 3), Error);
  EXPECT_THROW(chi2_quantile(0.5, 0), Error);
  EXPECT_THROW(fit_ar1(std::vector<double>(5, 1.0), Detrend::mean), Error);
  SpectrumSettings s;
  s.confidence = 1.5;
  PressureSeries ser{"x", {}, {"A"}, {{}}};
  for (int t = 0; t < 256; ++t) ser.t.push_back(t * 1e-3), ser.p[0].push_back(std::sin(t));
  try {
    analyse_series({ser}, {"x"}, s);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    std::printf("error: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("--confidence: 1.5"), std::string::npos);
  }
}

}  // namespace
}  // namespace cgdem::scaling

namespace cgdem::scaling {
namespace {

// The pressure spectra section of `cgdem scale` on two runs whose cell B holds only a
// transient (a 20 ms pulse on weak red noise) and whose cell A adds a sine at 650 Hz: B
// reads "no significant peak" in both runs (no deviation computed from it), A is found.
TEST(RedNoiseTest, ScaleSectionSaysNoSignificantPeak) {
  const std::string dir = io::test::scratch_dir();
  std::vector<std::string> dirs;
  for (int r = 0; r < 2; ++r) {
    const std::string d = dir + "/l=" + std::to_string(r + 1);
    std::filesystem::create_directories(d);
    const std::vector<double> pulse = pulse_in_noise(15.0, 0.02, 40 + r);
    std::string s = "# synthetic run\nt,mass_in_die,transfer_rate,p_A,p_B\n";
    for (size_t i = 0; i < pulse.size(); ++i) {
      const double t = i * 1e-4;
      s += fmt::format("{:.6f},0,0,{:.17g},{:.17g}\n", t, pulse[i] + 0.3 * std::sin(2 * std::numbers::pi * 650 * t),
                       pulse[i]);
    }
    io::test::spit(d + "/diagnostics.csv", s);
    dirs.push_back(d);
  }
  const PressureSpectra p = analyse_pressure_spectra(dirs, {"l=1", "l=2"}, 0.0);
  ASSERT_EQ(p.not_applicable, "");
  const auto dev = spectrum_deviations(p.analysis, "l=1");
  const std::string md = pressure_spectra_section(p, dev, 0.0, "l=1");
  for (const auto& d : dev)
    std::printf("scale section %s %s: f %.6g Hz, variance deviation %.3g\n", d.run.c_str(), d.cell.c_str(), d.f,
                d.variance_dev);
  EXPECT_NE(md.find("| l=1 | B | 10 | no significant peak |"), std::string::npos) << md;
  EXPECT_NE(md.find("| l=2 | B | 10 | no significant peak |"), std::string::npos) << md;
  for (const auto& d : dev) {
    if (d.cell == "A") EXPECT_NEAR(d.f_interp, 650.0, 1e4 / 512);  // within a bin
    if (d.cell == "B") EXPECT_TRUE(std::isnan(d.f) && std::isnan(d.band_power_dev));
    if (d.run == "l=2") EXPECT_TRUE(std::isfinite(d.variance_dev));
  }
}

}  // namespace
}  // namespace cgdem::scaling
