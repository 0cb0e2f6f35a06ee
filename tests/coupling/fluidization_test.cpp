// Minimum fluidization of a small free bed of l = 3 parcels (d_O = 125 um, rho_p = 1500,
// k 50 N/m, e 0.9, mu 0.3; air rho 1.0, mu 1.8e-5), and the same bed at small and large
// fluid steps.
//
// Set-up (bed_util.hpp): 756 parcels (d = 375 um) in a 2.4 x 2.4 mm box periodic in x and
// y on a 0.6 mm grid (dx/d = 1.6, the die-filling resolution), a DEM floor at z = 0 that
// the air passes through (inflow: the bottom Wall side with a normal velocity; outflow: an
// Open top). The parcels settle under gravity in air at rest into a bed ~6 mm high
// (~16 parcel layers, ~10 cells).
//
// Fluidization curve: the superficial velocity U (the inflow flux, re-imposed every 1 ms
// because the flux of a Wall side is eps_0 U_w) is raised in steps; the bed pressure drop
// dp = p(bottom cells) - p(top cells) - rho_f g dz is averaged over the end of each step.
// U_mf is where the linear fit of the fixed-bed branch (2.5, 5, 7.5 mm/s) reaches the
// buoyant weight per area W/A. References:
//   * Wen & Yu (1966; docs/references.md): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, 7.7 mm/s.
//     Its constants stand for Ergun's force balance at a FIXED packing (for spheres
//     (1-eps)/eps^3 = 11, i.e. eps_mf = 0.383, in the viscous regime that holds here,
//     Ar = 89); a bed of frictional spheres (mu = 0.3) poured under gravity packs looser.
//   * Ergun's force balance at the bed's own void fraction eps_b (what eqs. 8-9 imply):
//     (1-eps) (rho_p - rho_f) g = 150 mu (1-eps)^2 U/(eps^3 d^2) + 1.75 rho (1-eps) U^2/(eps^3 d),
//     eps_b = 1 - V_solid / (A 2 z_cm) (a uniform bed of height H has z_cm = H/2).
// Above U_mf (at 2 U_mf) the bed must expand (z_cm rises) and dp stay near W/A.
//
// Measured (this set-up, 1 December): poured bed eps_b = 0.4188, U_mf = 11.17 mm/s: +4.0 %
// against Ergun at eps_b (asserted, 15 %), +45 % against Wen-Yu (reported only: the packing
// is not the one Wen-Yu's constants stand for). Dense bed (settled with mu = 0, fluidized
// with mu = 0.3): eps_b = 0.3806, U_mf = 8.14 mm/s: +5.5 % against Wen-Yu's 7.72 mm/s
// (asserted, the 15 %), +7.6 % against Ergun at eps_b; it expands by 9.3 % at 2 U_mf.
// Known shortfalls of the coupling near the floor: ~3 % of the parcels' drag is deposited
// on the bottom boundary z-faces (the TSC kernel folds the nodes below the floor onto them),
// which the air solver does not update (prescribed Wall faces), so the air never feels it
// and dp above U_mf is ~0.97 W/A.
// Stability at the largest fluid step: FreeBedStableAtTheLargestFluidStep.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "bed_util.hpp"

using namespace cgdem;

namespace {

constexpr double kDo = 125e-6, kRhoP = 1500, kRhoF = 1.0, kMu = 1.8e-5, kG = 9.81;

double wen_yu_umf() {
  const double ar = kRhoF * (kRhoP - kRhoF) * kG * kDo * kDo * kDo / (kMu * kMu);
  const double re = std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7;
  return re * kMu / (kRhoF * kDo);
}

// Root of (1-e) drho g = 150 mu (1-e)^2 U/(e^3 d^2) + 1.75 rho (1-e) U^2/(e^3 d).
double ergun_umf(double e) {
  const double a = 1.75 * kRhoF / (e * e * e * kDo);
  const double b = 150 * kMu * (1 - e) / (e * e * e * kDo * kDo);
  const double c = -(kRhoP - kRhoF) * kG;
  return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

double wall_seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Holds superficial velocity U for `duration` (re-imposing the inflow flux every 1 ms) and
// returns the state averaged over the fluid steps of the last `average` seconds.
test::BedState hold(test::Bed& bed, double U, double duration, double average) {
  auto& cs = *bed.sys->cs;
  const double t_end = cs.time() + duration, t_avg = t_end - average;
  test::BedState avg;
  int n = 0;
  while (cs.time() < t_end - 1e-9) {
    test::set_superficial(bed, U);
    const double t_next = std::min(t_end, cs.time() + 1e-3);
    while (cs.time() < t_next - 1e-9) {
      cs.step();
      if (cs.time() < t_avg - 1e-9) continue;
      const test::BedState s = test::measure(bed);
      avg.dp += s.dp, avg.superficial += s.superficial, avg.z_mean += s.z_mean, avg.ke += s.ke;
      avg.support += s.support, avg.eps_bulk += s.eps_bulk;
      avg.v_max = std::max(avg.v_max, s.v_max);
      avg.finite = avg.finite && s.finite;
      ++n;
    }
  }
  for (double* q : {&avg.dp, &avg.superficial, &avg.z_mean, &avg.ke, &avg.support, &avg.eps_bulk}) *q /= n;
  return avg;
}

// A settled bed (shared by the tests of this file: settling is the expensive part).
struct Settled {
  test::Bed bed;
  Particles packed;  // the parcels as settled (the bed itself goes on to be fluidized)
  test::BedState state;
  double wall = 0;
  long removed_settling = 0;  // parcels lost while settling (before a rebuild)
};

// Settles the lattice in air at rest for 0.09 s with `settle_material`; the bed that goes on
// to be fluidized has the paper's material (mu = 0.3) in both cases, rebuilt from the
// settled parcels when the settling used another one.
Settled settle(const char* name, const MaterialParams& settle_material) {
  Settled r;
  const auto t0 = std::chrono::steady_clock::now();
  test::BedSpec spec;
  spec.material = settle_material;
  r.bed = test::make_bed(spec);
  auto& cs = *r.bed.sys->cs;
  while (cs.time() < 0.09 - 1e-9) cs.step();
  r.state = test::measure(r.bed);
  r.packed = r.bed.sys->dem->particles();
  r.removed_settling = r.bed.sys->dem->removed();
  if (settle_material.friction != MaterialParams{}.friction ||
      settle_material.wall_friction != MaterialParams{}.wall_friction) {
    r.bed = test::make_bed(test::BedSpec{}, &r.packed);
    r.bed.sys->cs->step();  // the new air field adjusts to the bed (eps mapped, pressure solved)
    r.state = test::measure(r.bed);
  }
  r.wall = wall_seconds(t0);
  std::printf("[ fluidization ] %s: settled %zu parcels in air for 0.09 s with mu %.2f (%.1f s wall): z_cm %.4f mm, "
              "eps_b %.4f, bottom-cell eps %.4f, KE/parcel %.1e J, W/A %.2f Pa; removed %ld\n",
              name, r.bed.sys->dem->particles().size(), settle_material.friction, r.wall, 1e3 * r.state.z_mean,
              r.state.eps_bulk, r.state.eps_floor, r.state.ke, r.bed.weight / r.bed.area, r.removed_settling);
  return r;
}

// Poured with the paper's friction (mu = 0.3): packs at eps_b ~0.42.
Settled& settled_bed() {
  static Settled s = settle("poured bed", MaterialParams{});
  return s;
}

// Poured without friction (mu = 0 against parcels and floor while settling, 0.3 after):
// random close packing, eps_b near the 0.383 that Wen-Yu's constants stand for.
Settled& dense_bed() {
  static Settled s = [] {
    MaterialParams m;
    m.friction = m.wall_friction = 0;
    return settle("dense bed", m);
  }();
  return s;
}

struct Curve {
  std::vector<double> U, dp, support;
  double slope = 0, intercept = 0, umf = 0, umf_support = 0, eps_b = 0, w_over_a = 0;
  double z_packed = 0, z_expanded = 0, dp_fluidized = 0, u_fluidized = 0;
  bool finite = true;
};

Curve measure_curve(Settled& st, const char* name) {
  Curve r;
  test::Bed& bed = st.bed;
  const auto t0 = std::chrono::steady_clock::now();
  r.w_over_a = bed.weight / bed.area;
  r.eps_b = st.state.eps_bulk;
  r.z_packed = st.state.z_mean;
  for (double U : {2.5e-3, 5e-3, 7.5e-3}) {
    const test::BedState s = hold(bed, U, 3e-3, 1e-3);
    r.U.push_back(s.superficial);
    r.dp.push_back(s.dp);
    r.support.push_back(s.support / bed.area);
    r.finite = r.finite && s.finite;
    std::printf("[ fluidization ] %s, fixed bed: U %.3f mm/s, dp %.3f Pa (%.3f W/A), parcels carried by the air %.3f W/A, "
                "z_cm %.4f mm\n",
                name, 1e3 * s.superficial, s.dp, s.dp / r.w_over_a, s.support / bed.weight, 1e3 * s.z_mean);
  }
  // Least-squares line dp = slope U + intercept; U_mf where it reaches W/A.
  const double n = r.U.size(), mu = std::accumulate(r.U.begin(), r.U.end(), 0.0) / n;
  const double mp = std::accumulate(r.dp.begin(), r.dp.end(), 0.0) / n;
  const double ms = std::accumulate(r.support.begin(), r.support.end(), 0.0) / n;
  double suu = 0, sup = 0, sus = 0;
  for (size_t i = 0; i < r.U.size(); ++i) {
    suu += (r.U[i] - mu) * (r.U[i] - mu);
    sup += (r.U[i] - mu) * (r.dp[i] - mp);
    sus += (r.U[i] - mu) * (r.support[i] - ms);
  }
  r.slope = sup / suu;
  r.intercept = mp - r.slope * mu;
  r.umf = (r.w_over_a - r.intercept) / r.slope;
  r.umf_support = (r.w_over_a - (ms - sus / suu * mu)) / (sus / suu);
  // Above U_mf: 2 U_mf for 40 ms; dp averaged over the last 20 ms.
  const test::BedState s = hold(bed, 2 * r.umf, 40e-3, 20e-3);
  r.dp_fluidized = s.dp;
  r.u_fluidized = s.superficial;
  r.z_expanded = test::measure(bed).z_mean;
  r.finite = r.finite && s.finite;
  std::printf("[ fluidization ] %s at 2 U_mf (U %.2f mm/s, 40 ms; averages over the last 20 ms): dp %.2f Pa = %.4f W/A, "
              "z_cm %.4f -> %.4f mm (+%.1f %%), eps_b %.4f, max parcel speed %.1f mm/s; curve %.1f s wall\n",
              name, 1e3 * s.superficial, s.dp, s.dp / r.w_over_a, 1e3 * r.z_packed, 1e3 * r.z_expanded,
              100 * (r.z_expanded / r.z_packed - 1), s.eps_bulk, 1e3 * s.v_max, wall_seconds(t0));
  return r;
}

Curve& fluidization_curve() {
  static Curve c = measure_curve(settled_bed(), "poured bed");
  return c;
}

Curve& dense_fluidization_curve() {
  static Curve c = measure_curve(dense_bed(), "dense bed");
  return c;
}

}  // namespace

TEST(Fluidization, MinimumVelocityOfAFreeBedAndExpansionAboveIt) {
  const Curve& c = fluidization_curve();
  ASSERT_TRUE(c.finite);
  EXPECT_EQ(settled_bed().bed.sys->dem->removed(), 0);  // W is that of every parcel
  const double wy = wen_yu_umf(), eg = ergun_umf(c.eps_b);
  std::printf("[ fluidization ] fixed-bed fit: dp = %.1f Pa/(m/s) U %+.3f Pa; U_mf = %.2f mm/s (from the parcels' air "
              "forces: %.2f mm/s)\n",
              c.slope, c.intercept, 1e3 * c.umf, 1e3 * c.umf_support);
  std::printf("[ fluidization ] poured bed: U_mf vs Wen-Yu %.2f mm/s: rel err %+.3f (reported: Wen-Yu stands for "
              "eps 0.383, see WenYu...OfADenseBed)\n",
              1e3 * wy, c.umf / wy - 1);
  std::printf("[ fluidization ] U_mf vs Ergun force balance at the bed's eps_b = %.4f: %.2f mm/s, rel err %+.3f "
              "(tol 0.15)\n",
              c.eps_b, 1e3 * eg, c.umf / eg - 1);
  EXPECT_LT(test::rel_err(c.umf, eg), 0.15);
  // The fixed branch is a line through the origin (Ergun's viscous term dominates: the
  // inertial term is 1e-3 of it at 1 cm/s).
  EXPECT_LT(std::fabs(c.intercept), 0.02 * c.w_over_a);
  // Above U_mf: dp carries the bed's weight; the bed expands.
  std::printf("[ fluidization ] above U_mf: dp / (W/A) = %.4f (tol 0.10), z_cm rises %.1f %% (required > 5 %%)\n",
              c.dp_fluidized / c.w_over_a, 100 * (c.z_expanded / c.z_packed - 1));
  EXPECT_LT(test::rel_err(c.dp_fluidized, c.w_over_a), 0.10);
  EXPECT_GT(c.z_expanded, 1.05 * c.z_packed);
}

// Wen-Yu's correlation against a bed at the packing its constants stand for. Its constants
// are Ergun's at (1-eps)/eps^3 = 11, i.e. eps_mf = 0.383 for spheres (the viscous term
// holds here), and U_mf in this regime scales as eps^3/(1-eps): the poured bed of the first
// test (eps_b ~0.42) is not such a bed, so comparing it with Wen-Yu measures the packing,
// not the coupling. This bed is settled without friction (random close packing), then
// fluidized with the paper's mu = 0.3, and its U_mf is compared with Wen-Yu (the issue's
// 15 %) and with Ergun at its own eps_b.
TEST(Fluidization, WenYuMinimumFluidizationVelocityOfADenseBedWithin15Percent) {
  const Curve& c = dense_fluidization_curve();
  ASSERT_TRUE(c.finite);
  EXPECT_EQ(dense_bed().removed_settling + dense_bed().bed.sys->dem->removed(), 0);
  const double wy = wen_yu_umf(), eg = ergun_umf(c.eps_b);
  std::printf("[ fluidization ] dense bed: eps_b %.4f (Wen-Yu's constants: 0.383); fixed-bed fit dp = %.1f Pa/(m/s) U "
              "%+.3f Pa; U_mf = %.2f mm/s\n",
              c.eps_b, c.slope, c.intercept, 1e3 * c.umf);
  std::printf("[ fluidization ] dense bed: U_mf vs Wen-Yu %.2f mm/s: rel err %+.3f (tol 0.15); vs Ergun at eps_b "
              "%.2f mm/s: rel err %+.3f (tol 0.15)\n",
              1e3 * wy, c.umf / wy - 1, 1e3 * eg, c.umf / eg - 1);
  EXPECT_LT(test::rel_err(c.umf, wy), 0.15);
  EXPECT_LT(test::rel_err(c.umf, eg), 0.15);
  EXPECT_GT(c.z_expanded, 1.05 * c.z_packed);  // and it expands above U_mf
}

namespace {

// The settled free bed at U = 5 mm/s (below U_mf) run for `duration` from the packed state
// at a given fluid step: it must stay at rest (no NaN, kinetic energy below that of parcels
// moving at 1 mm/s once the start-up is over: after the first 4 ms AND the first 4 fluid
// steps, since switching the flow on shakes the bed for a few steps of any size) and give
// the same pressure drop at every step.
struct FreeBedRun {
  double dp = 0, dt = 0, ke_max = 0, ke_ref = 0, v_max = 0;
  bool finite = true;
};

FreeBedRun free_bed(double dt_max, double duration = 12e-3, DragCoupling coupling = DragCoupling::SemiImplicit) {
  Settled& st = settled_bed();
  test::BedSpec spec;
  spec.dt_fluid_max = dt_max;
  spec.coupling = coupling;
  test::Bed bed = test::make_bed(spec, &st.packed);
  test::set_superficial(bed, 5e-3);
  auto& cs = *bed.sys->cs;
  FreeBedRun r;
  int steps = 0;
  while (cs.time() < duration - 1e-9) {
    r.dt = cs.step().dt_fluid;
    const test::BedState s = test::measure(bed);
    r.finite = r.finite && s.finite;
    if (++steps > 4 && cs.time() > 4e-3) r.ke_max = std::max(r.ke_max, s.ke), r.v_max = std::max(r.v_max, s.v_max);
  }
  const test::BedState s = test::measure(bed);
  r.dp = s.dp;
  r.ke_ref = 0.5 * bed.sys->dem->species()[0].mass() * 1e-6;
  std::printf("[ fluidization ] free bed (%s drag), U %.3f mm/s, fluid step %.2e s, %d steps: dp %.3f Pa (%.4f W/A), after the "
              "start-up max KE/parcel %.1e J (tol %.1e: 1 mm/s), max parcel speed %.2f mm/s\n",
              coupling == DragCoupling::Implicit ? "implicit" : "semi-implicit", 1e3 * s.superficial, r.dt, steps, r.dp, r.dp / bed.weight * bed.area, r.ke_max, r.ke_ref, 1e3 * r.v_max);
  return r;
}

}  // namespace

TEST(Fluidization, FreeBedSamePressureDropAtFluidSteps1em5And1em4) {
  const FreeBedRun a = free_bed(1e-5), b = free_bed(1e-4);
  for (const FreeBedRun* r : {&a, &b}) {
    EXPECT_TRUE(r->finite);
    EXPECT_LT(r->ke_max, r->ke_ref);
  }
  std::printf("[ fluidization ] free bed: dp at %.2e s vs %.2e s: rel diff %.2e (tol 1e-2)\n", a.dt, b.dt,
              test::rel_err(a.dp, b.dp));
  EXPECT_LT(test::rel_err(a.dp, b.dp), 1e-2);
}

// The third step, the largest the air solver allows (its explicit viscous limit,
// 2.67e-3 s here, 2,670 DEM substeps per fluid step), run for 24 ms (9 fluid steps; the
// start-up takes 4 of them, whatever their size). Measured (1 December): dp 23.46 Pa
// against 23.35 Pa at 1e-4 s (+0.5 %, tol 1 %), after the start-up KE/parcel <= 7e-16 J
// (tol 2.1e-14 J) and parcels below 4 mm/s, falling to 1e-17 J and 0.5 mm/s by 16 ms.
// History: with the pressure-gradient part of the end-of-step correction the bed developed
// a period-2 oscillation growing ~2x per fluid step (exchange.hpp); once that was removed
// it stayed bounded, but the drag correction, then a full kick dt_f c_p (u^{n+1} - u_f),
// multiplied every change of the air velocity by dt_f c_p / m_p (~270 here) and shook the
// bed (dp +2.1 %, parcels at 12 mm/s). The correction is now the parcel's backward-Euler
// response to that change (exchange.hpp), which is bounded by m_p (u^{n+1} - u_f).
TEST(Fluidization, FreeBedStableAtTheLargestFluidStep) {
  const FreeBedRun b = free_bed(1e-4), c = free_bed(1.0, 24e-3);
  EXPECT_GT(c.dt, 100 * 1e-5);
  EXPECT_TRUE(c.finite);
  EXPECT_LT(c.ke_max, c.ke_ref);
  std::printf("[ fluidization ] free bed: dp at %.2e s vs %.2e s: rel diff %.2e (tol 1e-2)\n", c.dt, b.dt,
              test::rel_err(c.dp, b.dp));
  EXPECT_LT(test::rel_err(c.dp, b.dp), 1e-2);
}

// The same at the largest step with the implicit drag coupling: bounded, parcels at rest
// after the start-up, and the pressure drop of the semi-implicit run at 1e-4 s within 1 %.
TEST(Fluidization, FreeBedStableAtTheLargestFluidStepWithImplicitDrag) {
  const FreeBedRun b = free_bed(1e-4), c = free_bed(1.0, 24e-3, DragCoupling::Implicit);
  EXPECT_GT(c.dt, 100 * 1e-5);
  EXPECT_TRUE(c.finite);
  EXPECT_LT(c.ke_max, c.ke_ref);
  std::printf("[ fluidization ] free bed, implicit drag: dp at %.2e s vs semi-implicit at %.2e s: rel diff %.2e "
              "(tol 1e-2)\n", c.dt, b.dt, test::rel_err(c.dp, b.dp));
  EXPECT_LT(test::rel_err(c.dp, b.dp), 1e-2);
}
