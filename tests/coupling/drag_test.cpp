// Drag correlations (paper eqs. 8-11) against closed forms and the numbers of
// docs/references.md: terminal velocity of a 125 um particle, Ergun pressure gradient of a fixed
// bed, Wen-Yu minimum fluidization velocity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "coupling/drag.hpp"

using namespace cgdem::coupling;

namespace {
const AirProperties air{1.0, 1.8e-5};
const double rho_p = 1500, g = 9.81;

// Speed where drag balances weight minus buoyancy for a lone sphere (eps -> 1), bisection.
double terminal(double d_o, double d_parcel) {
  const double V = M_PI * std::pow(d_parcel, 3) / 6;
  const double W = (rho_p - air.rho) * V * g;
  double lo = 0, hi = 20;
  for (int it = 0; it < 200; ++it) {
    const double v = 0.5 * (lo + hi);
    (V * beta_over_solid(DragLaw::ErgunWenYu, 1.0, v, d_o, air) * v > W ? hi : lo) = v;
  }
  return 0.5 * (lo + hi);
}
}  // namespace

TEST(Drag, TerminalVelocityIsTheSameForEveryRatio) {
  const double want = 0.520;  // docs/references.md, Terminal velocity (Re 3.6)
  double worst = 0;
  for (double l : {1.0, 2.0, 3.0}) {
    const double v = terminal(125e-6, l * 125e-6);
    const double err = std::fabs(v - want) / want;
    worst = std::max(worst, err);
    std::printf("[ drag ] l = %.0f: terminal velocity %.4f m/s (0.520; rel err %.2e)\n", l, v, err);
  }
  const double large = terminal(375e-6, 375e-6), real250 = terminal(250e-6, 250e-6);
  std::printf("[ drag ] simply large 375 um: %.3f m/s (2.11), real 250 um: %.3f m/s (1.34)\n", large, real250);
  EXPECT_LT(worst, 5e-3);  // the table gives 3 digits
  EXPECT_NEAR(large, 2.11, 0.01);
  EXPECT_NEAR(real250, 1.34, 0.01);
}

TEST(Drag, ErgunBedGradientMatchesTheReference) {
  // Fixed bed: -dp/dz = beta U / eps^2 with the interstitial slip U/eps (momentum balance
  // of the air), which must equal Ergun's equation: 9733 Pa/m at eps 0.4, U 1 cm/s.
  const double eps = 0.4, U = 0.01, d = 125e-6;
  const double beta = (1 - eps) * ergun_beta_over_solid(eps, U / eps, d, air);
  const double grad = beta * U / (eps * eps);
  const double ergun = 150 * air.mu * std::pow(1 - eps, 2) * U / (std::pow(eps, 3) * d * d) +
                       1.75 * air.rho * (1 - eps) * U * U / (std::pow(eps, 3) * d);
  std::printf("[ drag ] fixed bed gradient %.1f Pa/m, Ergun %.1f, docs/references.md: 9733\n", grad, ergun);
  EXPECT_NEAR(grad, ergun, 1e-9 * ergun);
  EXPECT_NEAR(grad, 9733, 1.0);
}

TEST(Drag, BranchesAndZeroSlipAreFinite) {
  // Continuity of the law at eps = 0.8 is not expected (the paper's switch), but both
  // branches must be finite and positive at zero slip and eps -> 1.
  for (double eps : {0.3, 0.8, 0.80001, 0.999, 1.0})
    for (double slip : {0.0, 1e-6, 1.0}) {
      const double b = beta_over_solid(DragLaw::ErgunWenYu, eps, slip, 125e-6, air);
      EXPECT_TRUE(std::isfinite(b) && b > 0) << eps << " " << slip;
    }
  // Wen-Yu at eps = 1, zero slip: Stokes, 18 mu / d^2.
  const double stokes = 18 * air.mu / (125e-6 * 125e-6);
  EXPECT_NEAR(wen_yu_beta_over_solid(1.0, 0.0, 125e-6, air), stokes, 1e-12 * stokes);
  EXPECT_THROW(parse_drag_law("stokes"), cgdem::Error);
}

TEST(Drag, WenYuMinimumFluidizationVelocity) {
  // Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7 (docs/references.md, Wen-Yu), d_O = 125 um: 7.7 mm/s.
  const double d = 125e-6;
  const double ar = std::pow(d, 3) * air.rho * (rho_p - air.rho) * g / (air.mu * air.mu);
  const double re = std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7;
  const double umf = re * air.mu / (air.rho * d);
  std::printf("[ drag ] Wen-Yu U_mf = %.2f mm/s (docs/references.md: 7.7)\n", umf * 1e3);
  EXPECT_NEAR(umf, 7.7e-3, 0.05e-3);
}
