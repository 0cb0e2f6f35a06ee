// Richardson analysis (scaling/richardson.hpp) on manufactured sequences
//   f(h) = f0 + C h^p (1 + delta h)
// whose order and limit are known: exact recovery for delta = 0 (constant and non-constant
// refinement ratios), the first-order bias of p for delta != 0 against its closed form, and
// detection of oscillatory, divergent and flat sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "scaling/richardson.hpp"

namespace cgdem::scaling {
namespace {

constexpr double kF0 = 1.7, kC = 0.3;

Level manufactured(double h, double p, double delta = 0) { return {h, kF0 + kC * std::pow(h, p) * (1 + delta * h)}; }

TEST(Richardson, ConstantRatioRecoversOrderAndLimit) {
  for (double p : {1.0, 2.0, 3.0}) {
    auto t = analyse_triple(manufactured(0.1, p), manufactured(0.05, p), manufactured(0.025, p));
    const double ep = std::fabs(t.order - p), ef = std::fabs(t.extrapolated - kF0);
    std::printf("[ error ] r = 2, p = %.0f: |p_obs - p| = %.2e (tol 1e-10), |f_ext - f0| = %.2e (tol 1e-12)\n", p, ep,
                ef);
    EXPECT_EQ(t.behaviour, Behaviour::Monotone);
    EXPECT_LT(ep, 1e-10);
    EXPECT_LT(ef, 1e-12);
    // Exact power law: f1 - f_ext = C h1^p, so GCI_21 = Fs C h1^p.
    const double gci = kGciSafetyFactor * kC * std::pow(0.025, p);
    std::printf("[ error ] GCI_21 relative error %.2e (tol 1e-9)\n", std::fabs(t.gci_fine / gci - 1));
    EXPECT_LT(std::fabs(t.gci_fine / gci - 1), 1e-9);
  }
}

TEST(Richardson, NonConstantRatioRecoversOrderAndLimit) {
  // Closed form of eq. (1): r21 = 1.5, r32 = 2, p = 1 gives e32/e21 = 1.5 * 1 / 0.5 = 3.
  const double p1 = observed_order(3.0, 1.5, 2.0);
  std::printf("[ error ] g(p) = 3 at r21 = 1.5, r32 = 2: |p - 1| = %.2e (tol 1e-12)\n", std::fabs(p1 - 1));
  EXPECT_LT(std::fabs(p1 - 1), 1e-12);
  // h of order 0.1 so that the differences (C h^p, down to 1e-4 at p = 4) stay far above
  // the round-off of f (1e-16): what is tested is the root of eq. (1), not cancellation.
  const double hs[][3] = {{0.03, 0.07, 0.1}, {0.1, 0.13, 0.5}, {0.2, 0.5, 0.6}};
  for (const auto& h : hs)
    for (double p : {0.7, 1.5, 2.0, 4.0}) {
      auto t = analyse_triple(manufactured(h[0], p), manufactured(h[1], p), manufactured(h[2], p));
      const double ep = std::fabs(t.order - p), ef = std::fabs(t.extrapolated - kF0);
      std::printf("[ error ] h = %g, %g, %g (r21 %.3f, r32 %.3f), p = %.1f: |p_obs - p| = %.2e (tol 1e-9), "
                  "|f_ext - f0| = %.2e (tol 1e-10)\n",
                  h[0], h[1], h[2], t.r21, t.r32, p, ep, ef);
      EXPECT_EQ(t.behaviour, Behaviour::Monotone);
      EXPECT_LT(ep, 1e-9);
      EXPECT_LT(ef, 1e-10);
    }
}

// f = f0 + C h^2 (1 + delta h), r = 2: e32/e21 = 4 (3 + 14 delta h1)/(3 + 7 delta h1), so
// p_obs = 2 + log2(1 + 7 delta h1 / (3 + 7 delta h1)) exactly, i.e. 2 + (7/(3 ln 2)) delta h1
// + O(h1^2); and with that p the extrapolation error is O(delta h1^3).
TEST(Richardson, HigherOrderTermGivesTheExpectedBias) {
  const double delta = 1.0;
  double last_bias = 1e30;
  for (double h1 : {1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128}) {
    auto t = analyse_triple(manufactured(h1, 2, delta), manufactured(2 * h1, 2, delta), manufactured(4 * h1, 2, delta));
    const double p_expected = 2 + std::log2(1 + 7 * delta * h1 / (3 + 7 * delta * h1));
    const double ef = std::fabs(t.extrapolated - kF0);
    std::printf("[ error ] h1 = 1/%.0f: p_obs = %.6f, closed form %.6f (|diff| %.1e, tol 1e-10); "
                "|f_ext - f0| = %.2e (tol 2 C delta h1^3 = %.2e)\n",
                1 / h1, t.order, p_expected, std::fabs(t.order - p_expected), ef, 2 * kC * delta * h1 * h1 * h1);
    EXPECT_LT(std::fabs(t.order - p_expected), 1e-10);
    EXPECT_LT(ef, 2 * kC * delta * h1 * h1 * h1);
    EXPECT_LT(t.order - 2, last_bias);  // the bias shrinks with refinement
    last_bias = t.order - 2;
  }
}

TEST(Richardson, MoreThanThreeLevels) {
  // Five levels, non-constant ratios, pure power law: every triple and the fit give p.
  const double p = 1.5, hs[] = {0.4, 0.3, 0.17, 0.1, 0.04};
  std::vector<Level> lv;
  for (double h : hs) lv.push_back(manufactured(h, p));
  auto triples = analyse_sequence(lv);
  ASSERT_EQ(triples.size(), 3u);
  for (const auto& t : triples) {
    std::printf("[ error ] triple h1 = %g: |p_obs - p| = %.2e (tol 1e-9)\n", t.fine.h, std::fabs(t.order - p));
    EXPECT_LT(std::fabs(t.order - p), 1e-9);
  }
  EXPECT_DOUBLE_EQ(triples[0].fine.h, 0.04);  // sorted fine to coarse whatever the input order
  PowerFit fit = fit_error_power_law(lv, kF0);
  std::printf("[ error ] fit: |p - 1.5| = %.2e, |C - 0.3| = %.2e, max log residual %.1e (tol 1e-10)\n",
              std::fabs(fit.order - p), std::fabs(fit.constant - kC), fit.max_log_residual);
  EXPECT_EQ(fit.levels, 5);
  EXPECT_EQ(fit.sign_changes, 0);
  EXPECT_LT(std::fabs(fit.order - p), 1e-10);
  EXPECT_LT(std::fabs(fit.constant - kC), 1e-10);
  EXPECT_LT(fit.max_log_residual, 1e-10);

  // With a higher-order term the triples' orders approach 2 from above as h shrinks
  // (t2[0] is the finest triple).
  std::vector<Level> lv2;
  for (int n = 8; n <= 128; n *= 2) lv2.push_back(manufactured(1.0 / n, 2, 1.0));
  auto t2 = analyse_sequence(lv2);
  for (size_t i = 0; i < t2.size(); ++i) {
    std::printf("[ info ] delta = 1, triple h1 = 1/%.0f: p_obs = %.4f\n", 1 / t2[i].fine.h, t2[i].order);
    EXPECT_GT(t2[i].order, 2);
    if (i > 0) EXPECT_GT(t2[i].order, t2[i - 1].order);
  }
}

TEST(Richardson, OscillatoryDivergentAndFlatAreDetected) {
  // Differences alternate in sign: f0 + C h^2 (-1)^k.
  auto osc = analyse_triple({0.1, 1.0 + 0.01}, {0.2, 1.0 - 0.04}, {0.4, 1.0 + 0.16});
  std::printf("[ info ] oscillatory: %s, spread %.3f (expected 0.20)\n", to_string(osc.behaviour).c_str(), osc.spread);
  EXPECT_EQ(osc.behaviour, Behaviour::Oscillatory);
  EXPECT_TRUE(std::isnan(osc.order));
  EXPECT_TRUE(std::isnan(osc.extrapolated));
  EXPECT_NEAR(osc.spread, 0.20, 1e-14);
  // Differences that grow under refinement (f = f0 + C/h: p = -1).
  auto div = analyse_triple({0.1, 1.0 + 0.01 / 0.1}, {0.2, 1.0 + 0.01 / 0.2}, {0.4, 1.0 + 0.01 / 0.4});
  EXPECT_EQ(div.behaviour, Behaviour::Divergent);
  EXPECT_TRUE(std::isnan(div.order));
  // Non-constant ratio: e32/e21 = 1.2 lies below g(0+) = ln 3 / ln 1.25 = 4.92, so p <= 0.
  auto div2 = analyse_triple({0.8, 1.0}, {1.0, 1.1}, {3.0, 1.22});
  EXPECT_EQ(div2.behaviour, Behaviour::Divergent);
  // All three equal, and a fine pair that agrees to round-off.
  EXPECT_EQ(analyse_triple({1, 2.0}, {2, 2.0}, {4, 2.0}).behaviour, Behaviour::Flat);
  EXPECT_EQ(analyse_triple({1, 2.0}, {2, 2.0 + 1e-15}, {4, 2.5}).behaviour, Behaviour::Flat);
  // No root of (1) for a negative ratio, nor at or below g(0+).
  EXPECT_TRUE(std::isnan(observed_order(-2.0, 2.0, 2.0)));
  EXPECT_TRUE(std::isnan(observed_order(1.0, 2.0, 2.0)));
  EXPECT_TRUE(std::isnan(observed_order(2.0, 1.5, 3.0)));  // g(0+) = ln 3 / ln 1.5 = 2.71
}

TEST(Richardson, BadLevelsAreErrors) {
  EXPECT_THROW(analyse_triple({0.1, 1}, {0.1, 2}, {0.2, 3}), Error);
  EXPECT_THROW(analyse_triple({-0.1, 1}, {0.1, 2}, {0.2, 3}), Error);
  EXPECT_THROW(analyse_triple({NAN, 1}, {0.1, 2}, {0.2, 3}), Error);
  EXPECT_THROW(analyse_triple({0.05, NAN}, {0.1, 2}, {0.2, 3}), Error);
  EXPECT_TRUE(analyse_sequence({{0.1, 1}, {0.2, 2}}).empty());
  EXPECT_TRUE(std::isnan(fit_error_power_law({{0.1, 1}, {0.2, 2}}, 2.0).order));  // one non-zero error
}

}  // namespace
}  // namespace cgdem::scaling
