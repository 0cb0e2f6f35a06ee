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

TEST(Drag, RegistryRowsAreInEnumOrderAndNamesRoundTrip) {
  const auto names = drag_law_names();
  ASSERT_EQ(names.size(), std::size(kDragLaws));
  for (std::size_t i = 0; i < std::size(kDragLaws); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(kDragLaws[i].law), i) << kDragLaws[i].name;
    EXPECT_EQ(parse_drag_law(names[i]), kDragLaws[i].law);
    std::printf("[ drag ] registry: %-13s %s\n", kDragLaws[i].name, kDragLaws[i].doc);
  }
  try {
    parse_drag_law("stokes");
    FAIL() << "no error for an unknown law";
  } catch (const cgdem::Error& e) {
    const std::string msg = e.what();
    for (const auto& n : names) EXPECT_NE(msg.find(n), std::string::npos) << msg;
  }
}

TEST(Drag, DiFeliceMatchesItsPerParticleForm) {
  // Di Felice (1994), written as the force on one sphere of diameter d in a bed of voidage
  // eps with superficial velocity U = eps |slip|: f = C_D rho (pi d^2 / 8) U^2 eps^-chi,
  // C_D = (0.63 + 4.8 Re^-1/2)^2, Re = rho d U / mu, chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2/2).
  // n f / |slip| with n = (1 - eps) / (pi d^3 / 6) spheres per volume is beta, so
  // beta / (1 - eps) must equal di_felice_beta_over_solid.
  const double d = 125e-6;
  double worst = 0;
  for (double eps : {0.4, 0.6, 0.8, 0.95, 1.0})
    for (double slip : {1e-4, 1e-2, 0.3, 5.0}) {
      const double U = eps * slip, re = air.rho * d * U / air.mu;
      const double cd = std::pow(0.63 + 4.8 / std::sqrt(re), 2);
      const double chi = 3.7 - 0.65 * std::exp(-std::pow(1.5 - std::log10(re), 2) / 2);
      const double f = cd * air.rho * M_PI * d * d / 8 * U * U * std::pow(eps, -chi);
      const double n = (1 - eps) / (M_PI * d * d * d / 6);
      const double got = di_felice_beta_over_solid(eps, slip, d, air);
      if (eps < 1) worst = std::max(worst, std::fabs(got - n * f / slip / (1 - eps)) / got);
      EXPECT_EQ(beta_over_solid(DragLaw::DiFelice, eps, slip, d, air), got);
    }
  std::printf("[ drag ] Di Felice against its per-particle form: worst rel err %.2e (tolerance 1e-12)\n", worst);
  EXPECT_LT(worst, 1e-12);
  // Zero slip: finite, the Re -> 0 limit 3/4 * 4.8^2 mu / (eps rho d) * rho / d * eps^(2 - 3.7),
  // 4 % below Stokes' 18 mu / d^2 at eps = 1 (Dallavalle's C_D tends to 23.04 / Re, not 24 / Re).
  for (double eps : {0.4, 1.0}) {
    const double want = 0.75 * 4.8 * 4.8 * air.mu / (eps * d * d) * std::pow(eps, -1.7);
    const double got = di_felice_beta_over_solid(eps, 0.0, d, air);
    std::printf("[ drag ] Di Felice at zero slip, eps %.1f: %.6e (limit %.6e) kg m^-3 s^-1\n", eps, got, want);
    EXPECT_NEAR(got, want, 1e-12 * want);
  }
  // The exponent's minimum 3.05 at Re = 10^1.5 (where the exp term is 1).
  const double slip15 = std::pow(10.0, 1.5) * air.mu / (air.rho * d);  // eps = 1
  const double cd15 = std::pow(0.63 + 4.8 / std::pow(10.0, 0.75), 2);
  EXPECT_NEAR(di_felice_beta_over_solid(1.0, slip15, d, air), 0.75 * cd15 * air.rho * slip15 / d,
              1e-12 * 0.75 * cd15 * air.rho * slip15 / d);
  EXPECT_NEAR(di_felice_beta_over_solid(0.5, slip15 / 0.5, d, air),
              0.75 * cd15 * air.rho * (slip15 / 0.5) / d * std::pow(0.5, 2 - 3.05),
              1e-9 * di_felice_beta_over_solid(0.5, slip15 / 0.5, d, air));
}
