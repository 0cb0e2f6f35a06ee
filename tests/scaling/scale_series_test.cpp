// Resampling and the deviation metrics of cgdem scale (scaling/series.hpp) on analytic series.
//  * Linear interpolation of sin t from 41 non-uniform samples on [0, 3]: error at 200 other
//    times <= h_max^2 / 8 (max |y''| = 1), exact at the samples.
//  * Normalized L2 distance of a = (1 + 0.03) b from b is 0.03 (discretely exact, 1e-12);
//    of b + 0.1 sin(2 pi t / T) from b = 1 over whole periods of a uniform grid it is
//    0.1 / sqrt(2) to 1e-12.
//  * Max deviation and its time; the peak of a sampled parabola.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "scaling/series.hpp"

namespace cgdem::scaling {
namespace {

TEST(ScalingSeries, ResampleIsLinearInterpolation) {
  Series s;
  for (int i = 0; i <= 40; ++i) {
    const double u = i / 40.0;
    s.t.push_back(3.0 * u * (0.6 + 0.4 * u));  // non-uniform, increasing
    s.y.push_back(std::sin(s.t.back()));
  }
  double hmax = 0;
  for (size_t i = 1; i < s.t.size(); ++i) hmax = std::max(hmax, s.t[i] - s.t[i - 1]);
  std::vector<double> tau;
  for (int j = 0; j < 200; ++j) tau.push_back(3.0 * j / 199.0);
  const auto y = resample(s, tau);
  double worst = 0;
  for (size_t j = 0; j < tau.size(); ++j) worst = std::max(worst, std::fabs(y[j] - std::sin(tau[j])));
  std::printf("linear resampling of sin: max error %.3e, bound h^2/8 = %.3e\n", worst, hmax * hmax / 8);
  EXPECT_LE(worst, hmax * hmax / 8);
  const auto at = resample(s, s.t);
  for (size_t i = 0; i < s.t.size(); ++i) EXPECT_DOUBLE_EQ(at[i], s.y[i]);
  EXPECT_THROW(resample(s, {3.5}), std::exception);
  EXPECT_THROW(resample({{0, 1, 1}, {0, 0, 0}}, {0.5}), std::exception);
}

TEST(ScalingSeries, CommonTimesAreTheOverlap) {
  const Series a{{0, 1, 2, 3, 4}, {0, 0, 0, 0, 0}}, b{{0.5, 2.5, 3.5}, {0, 0, 0}};
  const auto t = common_times(a.t, {a, b});
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.front(), 1.0);
  EXPECT_EQ(t.back(), 3.0);
}

TEST(ScalingSeries, DistancesOfAnalyticSeries) {
  const int n = 401;
  const double T = 0.25;
  std::vector<double> t(n), b(n), a(n), c(n);
  for (int i = 0; i < n; ++i) {
    t[i] = i * (2 * T) / (n - 1);  // two whole periods
    b[i] = 2.0 + std::cos(t[i]);
    a[i] = 1.03 * b[i];
    c[i] = 1.0 + 0.1 * std::sin(2 * std::numbers::pi * t[i] / T);
  }
  const double d1 = normalized_l2(t, a, b);
  std::vector<double> one(n, 1.0);
  const double d2 = normalized_l2(t, c, one);
  std::printf("normalized L2: %.15f (want 0.03), %.15f (want %.15f)\n", d1, d2, 0.1 / std::sqrt(2.0));
  EXPECT_NEAR(d1, 0.03, 1e-12);
  EXPECT_NEAR(d2, 0.1 / std::sqrt(2.0), 1e-12);
  const auto m = max_abs_deviation(c, one);
  EXPECT_NEAR(m.value, 0.1, 1e-4);  // the sample nearest the crest
  EXPECT_NEAR(t[m.index], T / 4, 0.5 * (t[1] - t[0]) + 1e-15);
  EXPECT_TRUE(std::isnan(normalized_l2(t, a, std::vector<double>(n, 0.0))));
}

TEST(ScalingSeries, PeakOfAParabola) {
  Series s;
  for (int i = 0; i <= 100; ++i) {
    s.t.push_back(0.01 * i);
    s.y.push_back(3.0 - 50.0 * (s.t.back() - 0.37) * (s.t.back() - 0.37));
  }
  const Peak p = peak(s);
  EXPECT_DOUBLE_EQ(p.t, s.t[37]);
  EXPECT_NEAR(p.value, 3.0, 1e-12);
  EXPECT_THROW(peak(Series{}), std::exception);
}

}  // namespace
}  // namespace cgdem::scaling
