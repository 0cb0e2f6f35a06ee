// Welch estimator (scaling/spectrum.hpp) against closed forms on synthetic signals:
//   * a sine of amplitude A at f0 in white Gaussian noise of variance sigma^2 (fixed seed):
//     peak at f0 within one bin, band power A^2/2, noise floor sigma^2/(fs/2), total
//     variance A^2/2 + sigma^2;
//   * Parseval (W4) for one segment, to round-off;
//   * coherence: ~1 at a shared sine, 1/K (its bias) between independent noises.
// The statistical tolerances are several standard deviations of the estimate (stated at
// each check), so that the fixed seed is not what makes them pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "scaling/spectrum.hpp"

using namespace cgdem::scaling;

namespace {

constexpr double kPi = std::numbers::pi;

// x[n] = A sin(2 pi f0 n / fs + phase) + sigma * N(0, 1)
std::vector<double> sine_in_noise(size_t n, double fs, double A, double f0, double phase, double sigma,
                                  std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = A * std::sin(2 * kPi * f0 * i / fs + phase) + sigma * g(rng);
  return x;
}

// Mean of v over bins [lo, hi) that are farther than `guard` bins from `skip`.
double mean_away_from(const std::vector<double>& v, int lo, int hi, int skip, int guard) {
  double s = 0;
  int n = 0;
  for (int m = lo; m < hi; ++m)
    if (std::abs(m - skip) > guard) {
      s += v[m];
      ++n;
    }
  return s / n;
}

struct SineCase {
  Window window;
  double f0_bins;  // f0 / df: off a bin for Hann, on a bin for rect (rect leaks off-bin)
};

class SineInNoise : public ::testing::TestWithParam<SineCase> {};

TEST_P(SineInNoise, PeakFrequencyPowerAndNoiseFloor) {
  const double fs = 1000.0, A = 1.0, sigma = 0.5;
  const int L = 1024;
  const size_t N = 1 << 16;
  const WelchParams p{fs, L, L / 2, GetParam().window, Detrend::mean};
  const Welch welch(p);
  const double f0 = GetParam().f0_bins * welch.df();
  std::mt19937_64 rng(20240607);
  const std::vector<double> x = sine_in_noise(N, fs, A, f0, 0.3, sigma, rng);
  const std::vector<double> P = welch.psd(x);
  const int K = welch.segments(N), h = main_lobe_half_width(p.window);

  const std::vector<Peak> peaks = find_peaks(P, welch.df(), h, 3);
  ASSERT_FALSE(peaks.empty());
  const Peak& pk = peaks[0];
  const double bin_err = std::abs(pk.f - f0) / welch.df(), interp_err = std::abs(pk.f_interp - f0) / welch.df();
  std::printf("[%s] K = %d, df = %.4f Hz: peak %.4f Hz (interpolated %.4f) vs f0 %.4f: %.3f bin (%.3f interpolated)\n",
              to_string(p.window).c_str(), K, welch.df(), pk.f, pk.f_interp, f0, bin_err, interp_err);
  EXPECT_LE(bin_err, 0.5 + 1e-12);  // the nearest bin: within one bin, and at most half
  EXPECT_LE(interp_err, 0.1);       // log-parabola on the main lobe: a tenth of a bin

  // Noise floor sigma^2 / (fs/2), from bins away from the peak and from DC (detrended).
  // Each bin's estimate has a relative spread ~1/sqrt(K) ~ 0.09, averaged over ~500 bins
  // (neighbours correlated for Hann): ~0.5 %; tolerance 3 %.
  const double floor_ref = sigma * sigma / (fs / 2);
  const double floor = mean_away_from(P, 4, welch.bins() - 1, pk.bin, 20);
  const double floor_err = std::abs(floor / floor_ref - 1);
  std::printf("noise floor %.6e vs sigma^2/(fs/2) = %.6e: relative error %.4f (tol 0.03)\n", floor, floor_ref,
              floor_err);
  EXPECT_LT(floor_err, 0.03);

  // Band power of the peak minus the noise in the band: A^2/2. The noise part of the band
  // (2h+1 bins) fluctuates by ~1e-3 * sigma^2-ish; leakage outside the main lobe is < 0.1 %
  // for Hann and zero for an on-bin rect; tolerance 1 %.
  const double sine_power = pk.band_power - floor * (2 * h + 1) * welch.df();
  const double power_err = std::abs(sine_power / (A * A / 2) - 1);
  std::printf("peak band power %.6f (minus noise %.6f) vs A^2/2 = %.6f: relative error %.5f (tol 0.01)\n",
              pk.band_power, sine_power, A * A / 2, power_err);
  EXPECT_LT(power_err, 0.01);

  // The integral of the PSD is the variance (W4): A^2/2 + sigma^2; its sample spread
  // is ~sigma^2 sqrt(2/N) ~ 0.1 % of the total; tolerance 1 %.
  const double var = integrate(P, welch.df()), var_ref = A * A / 2 + sigma * sigma;
  std::printf("integral of the PSD %.6f vs A^2/2 + sigma^2 = %.6f: relative error %.5f (tol 0.01)\n", var, var_ref,
              std::abs(var / var_ref - 1));
  EXPECT_LT(std::abs(var / var_ref - 1), 0.01);
}

INSTANTIATE_TEST_SUITE_P(Windows, SineInNoise,
                         ::testing::Values(SineCase{Window::hann, 126.37}, SineCase{Window::hann, 126.5},
                                           SineCase{Window::rect, 126.0}),
                         [](const auto& info) {
                           return to_string(info.param.window) + (info.index == 1 ? "_half_bin" : "");
                         });

// (W4) with one segment: sum_m P df equals sum_n (w x)^2 / U to round-off. For the
// rectangular window that is the mean square (Parseval); odd and even lengths (the Nyquist
// bin is counted once only for even L).
TEST(WelchParseval, OneSegmentSumsToTheMeanSquare) {
  std::mt19937_64 rng(7);
  for (int L : {1000, 999, 64}) {
    for (Window w : {Window::rect, Window::hann}) {
      const std::vector<double> x = sine_in_noise(L, 250.0, 0.7, 31.0, 1.0, 1.3, rng);
      const Welch welch({250.0, L, 0, w, Detrend::none});
      ASSERT_EQ(welch.segments(x.size()), 1);
      const std::vector<double> c = window_coefficients(w, L);
      double sum_wx2 = 0, sum_w2 = 0;
      for (int n = 0; n < L; ++n) {
        sum_wx2 += c[n] * c[n] * x[n] * x[n];
        sum_w2 += c[n] * c[n];
      }
      const double expect = sum_wx2 / sum_w2;  // = (1/L) sum x^2 for rect
      const double got = integrate(welch.psd(x), welch.df());
      const double err = std::abs(got / expect - 1);
      std::printf("L = %4d %s: sum P df = %.15f, sum (w x)^2 / U = %.15f, relative error %.2e (tol 1e-12)\n", L,
                  to_string(w).c_str(), got, expect, err);
      EXPECT_LT(err, 1e-12);
    }
  }
}

// Coherence (W6): ~1 at a sine shared by two signals with independent noise (expected
// value SNR_x SNR_y / ((1 + SNR_x)(1 + SNR_y)) with SNR the sine's bin power over the noise's
// there), and 1/K elsewhere (for non-overlapping segments and Gaussian noise, C follows a
// Beta(1, K - 1) law: mean 1/K, standard deviation ~1/K).
TEST(WelchCoherence, SharedSineNearOneIndependentNoiseAtTheBias) {
  const double fs = 1000.0, A = 1.0, sigma = 1.0;
  const int L = 1024;
  const size_t N = 1 << 16;
  const Welch welch({fs, L, 0, Window::rect, Detrend::mean});
  const int K = welch.segments(N), m0 = 200;
  const double f0 = m0 * welch.df();
  std::mt19937_64 rng(99);
  const std::vector<double> x = sine_in_noise(N, fs, A, f0, 0.0, sigma, rng);
  const std::vector<double> y = sine_in_noise(N, fs, A, f0, 1.1, sigma, rng);
  const std::vector<double> C = coherence(welch.psd(x), welch.psd(y), welch.csd(x, y));

  const double snr = (A * A / 2) / (sigma * sigma / (fs / 2) * welch.df());  // on-bin rect: all in one bin
  const double c_ref = snr * snr / ((1 + snr) * (1 + snr));
  std::printf("K = %d: coherence at f0 %.5f (expected %.5f, tol 0.01)\n", K, C[m0], c_ref);
  EXPECT_NEAR(C[m0], c_ref, 0.01);

  // ~510 bins: the mean's standard deviation is ~(1/K)/sqrt(510) ~ 4.4 % of 1/K; tol 20 %.
  const double bias = mean_away_from(C, 1, welch.bins() - 1, m0, 2);
  std::printf("mean coherence away from f0 %.5f vs 1/K = %.5f: relative error %.4f (tol 0.2)\n", bias, 1.0 / K,
              std::abs(bias * K - 1));
  EXPECT_NEAR(bias * K, 1.0, 0.2);

  // The cross-spectrum of a signal with itself is its PSD (real, to round-off).
  const std::vector<double> Pxx = welch.psd(x);
  const std::vector<std::complex<double>> Pxx_c = welch.csd(x, x);
  double worst = 0;
  for (int m = 0; m < welch.bins(); ++m) worst = std::max(worst, std::abs(Pxx_c[m] - Pxx[m]) / Pxx[m]);
  std::printf("max |P_xx (csd) - P_xx (psd)| / P_xx = %.2e (tol 1e-12)\n", worst);
  EXPECT_LT(worst, 1e-12);
}

// Overlapping Hann segments are correlated: the coherence bias is 1/K_eff > 1/K. For white
// noise the transforms of neighbouring segments (S = L/2 apart) correlate by
// r = sum_{n < L-S} w[n] w[n+S] / sum w^2 = (L/16) / (3L/8) = 1/6 (Welch 1967, Table 1), their
// periodograms by r^2 = 1/36; with neighbours only, the K-segment mean's variance and the
// coherence bias are (1 + 2 r^2)/K = (19/18)/K. 4097 bins (~2,100 independent for Hann)
// give the mean a ~2 % scatter; tolerance 10 % (measured by numpy on other seeds: 1.047/K
// +- 0.024, L = 256, 20 series).
TEST(WelchCoherence, OverlapRaisesTheBiasToOneOverKeff) {
  const double fs = 500.0;
  const int L = 8192;
  const size_t N = 1 << 22;
  const Welch welch({fs, L, L / 2, Window::hann, Detrend::mean});
  const int K = welch.segments(N);
  std::mt19937_64 rng(3);
  const std::vector<double> x = sine_in_noise(N, fs, 0.0, 0.0, 0.0, 1.0, rng);
  const std::vector<double> y = sine_in_noise(N, fs, 0.0, 0.0, 0.0, 1.0, rng);
  const std::vector<double> C = coherence(welch.psd(x), welch.psd(y), welch.csd(x, y));
  const double bias = mean_away_from(C, 2, welch.bins() - 2, -100, 0), ref = 19.0 / 18.0 / K;
  std::printf("K = %d (50 %% Hann): mean coherence %.3e vs (19/18)/K = %.3e: relative error %.4f (tol 0.1; 1/K = %.3e)\n",
              K, bias, ref, std::abs(bias / ref - 1), 1.0 / K);
  EXPECT_NEAR(bias / ref, 1.0, 0.1);
}

// Linear detrending removes a ramp exactly; mean removal leaves its 1/f^2 leakage.
TEST(WelchDetrend, LinearRemovesARamp) {
  const int L = 128;
  std::vector<double> x(4 * L);
  for (size_t i = 0; i < x.size(); ++i) x[i] = 3.0 + 0.25 * i;
  const double lin = integrate(Welch({100.0, L, L / 2, Window::hann, Detrend::linear}).psd(x), 1.0);
  const double mean = integrate(Welch({100.0, L, L / 2, Window::hann, Detrend::mean}).psd(x), 1.0);
  std::printf("ramp: integrated PSD %.3e with linear detrending (tol 1e-20), %.3e with mean removal\n", lin, mean);
  EXPECT_LT(lin, 1e-20);
  EXPECT_GT(mean, 1.0);
}

// Peaks: two sines, the larger first, each at its own bin, band powers A^2/2.
TEST(WelchPeaks, TwoSinesInOrderOfPower) {
  const double fs = 2000.0;
  const int L = 500;  // df = 4 Hz, not a power of two
  std::vector<double> x(20 * L);
  for (size_t i = 0; i < x.size(); ++i)
    x[i] = 0.5 * std::sin(2 * kPi * 100.0 * i / fs) + 2.0 * std::sin(2 * kPi * 640.0 * i / fs + 0.2);
  const Welch welch({fs, L, L / 2, Window::hann, Detrend::mean});
  const std::vector<Peak> pk = find_peaks(welch.psd(x), welch.df(), 2, 5);
  ASSERT_GE(pk.size(), 2u);
  std::printf("peaks: %.2f Hz (band power %.6f, expected 2), %.2f Hz (%.6f, expected 0.125)\n", pk[0].f,
              pk[0].band_power, pk[1].f, pk[1].band_power);
  EXPECT_EQ(pk[0].f, 640.0);
  EXPECT_EQ(pk[1].f, 100.0);
  EXPECT_NEAR(pk[0].band_power, 2.0, 2.0 * 1e-6);
  EXPECT_NEAR(pk[1].band_power, 0.125, 0.125 * 1e-6);
}

TEST(WelchInput, BadParametersAreClearErrors) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const cgdem::Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message([] { parse_window("hamming"); }).find("--window: unknown window 'hamming'"), std::string::npos);
  EXPECT_NE(message([] { parse_detrend("cubic"); }).find("--detrend"), std::string::npos);
  EXPECT_NE(message([] { Welch({100.0, 64, 64, Window::hann, Detrend::mean}); }).find("--overlap"), std::string::npos);
  EXPECT_NE(message([] { Welch({100.0, 1, 0, Window::hann, Detrend::mean}); }).find("--segment"), std::string::npos);
  const std::string few = message([] { Welch({100.0, 64, 0, Window::hann, Detrend::mean}).segments(63); });
  std::printf("%s\n", few.c_str());
  EXPECT_NE(few.find("63 samples are fewer than one segment of 64"), std::string::npos);
}

}  // namespace
