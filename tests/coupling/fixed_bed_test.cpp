// Air through a fixed bed (parcels held in place), superficial velocity U = 1 cm/s,
// eps = 0.4, d_O = 125 um: the pressure gradient inside the bed must match Ergun's
// equation, 9733 Pa/m (docs/references.md, Fixed bed), for l = 1, 2, 3, and stay the same at fluid
// steps of 1e-5 s, 1e-4 s and the largest the step limits allow (the air's drag relaxation
// time in the bed is ~1e-5 s: only a semi-implicit drag survives the larger steps).
//
// Set-up: periodic in x and y; air enters through the bottom (a wall moving at U along z,
// i.e. prescribed inflow) and leaves through an open top (p = 0). The parcels sit on a
// simple cubic lattice of spacing a with pi d^3/6 = 0.6 a^3 (spheres of a fixed bed may
// overlap), and the grid spacing is a whole multiple of a, so the kernel maps exactly
// eps = 0.4 in the interior of the bed. The gradient is taken between cell centres two
// cells inside both ends of the bed.
#include <gtest/gtest.h>

#include <numbers>

#include "coupled_util.hpp"

using namespace cgdem;

namespace {

struct BedResult {
  double gradient = 0;   // -dp/dz in the bed [Pa/m]
  double eps_bed = 0;    // mean eps of the cells used
  double eps_spread = 0; // max - min of eps over them
  double dt = 0;
  int steps = 0;
};

BedResult fixed_bed(double ratio, int per_cell, double dt_fluid_max, int steps) {
  const double d = ratio * 125e-6;
  const double a = d * std::cbrt(std::numbers::pi / (6 * 0.6));
  const double dx = per_cell * a;
  const int nxy = 2, nz = 16, bed0 = 4, bed1 = 12;  // bed between cell faces 4 and 12
  test::SystemSpec s;
  s.grid = test::make_grid(nxy, nxy, nz, dx);
  s.air.bc = fluid::uniform_boundary(fluid::BcType::Periodic);
  s.air.bc[4] = {fluid::BcType::Wall, Vec3{0, 0, 0.01}, 0};
  s.air.bc[5] = {fluid::BcType::Open, Vec3{}, 0};
  s.air.pressure.method = "pcg-fft";
  s.air.pressure.rel_tol = 1e-10;
  s.air.dt_max = 1e30;
  s.species = {{"powder", 125e-6, ratio, 1500}};
  s.dem.dt = 1e-6;
  s.dem.gravity = {0, 0, 0};
  s.coupled.dt_fluid_max = dt_fluid_max;
  s.coupled.move_particles = false;
  auto sys = test::make_system(s, [&](Particles& p) {
    test::add_cubic_lattice(p, s.species[0], nxy * per_cell, (bed1 - bed0) * per_cell, a, bed0 * dx);
  });
  BedResult r;
  for (int n = 0; n < steps; ++n) r.dt = sys->cs->step().dt_fluid;
  r.steps = steps;
  const auto& air = sys->air;
  const int k0 = bed0 + 2, k1 = bed1 - 3;
  double pz0 = 0, pz1 = 0, emin = 1, emax = 0, esum = 0;
  int ne = 0;
  for (int j = 0; j < nxy; ++j)
    for (int i = 0; i < nxy; ++i) {
      pz0 += air.p(i, j, k0) / (nxy * nxy);
      pz1 += air.p(i, j, k1) / (nxy * nxy);
      for (int k = k0; k <= k1; ++k) {
        emin = std::min(emin, air.eps(i, j, k));
        emax = std::max(emax, air.eps(i, j, k));
        esum += air.eps(i, j, k);
        ++ne;
      }
    }
  r.gradient = (pz0 - pz1) / ((k1 - k0) * dx);
  r.eps_bed = esum / ne;
  r.eps_spread = emax - emin;
  return r;
}

}  // namespace

TEST(FixedBed, ErgunPressureGradientForEveryRatio) {
  const double want = 9733;  // Pa/m, Ergun at eps 0.4, U 1 cm/s, d_O 125 um
  double worst = 0;
  for (auto [l, m] : {std::pair{1.0, 5}, std::pair{2.0, 3}, std::pair{3.0, 2}}) {
    BedResult r = fixed_bed(l, m, 1e-4, 30);
    const double err = test::rel_err(r.gradient, want);
    worst = std::max(worst, err);
    std::printf("[ fixed bed ] l = %.0f: -dp/dz = %.1f Pa/m (Ergun 9733; rel err %.2e, tol 3e-2), bed eps %.5f "
                "(spread %.1e), dx/d = %.2f\n",
                l, r.gradient, err, r.eps_bed, r.eps_spread, m * std::cbrt(std::numbers::pi / 3.6));
  }
  EXPECT_LT(worst, 3e-2);
}

TEST(FixedBed, SamePressureDropAtSmallAndLargeFluidSteps) {
  // Largest step: the solver's own limits (CFL 0.5 and the explicit viscous limit).
  std::vector<BedResult> rs;
  for (auto [dt, steps] : {std::pair{1e-5, 60}, std::pair{1e-4, 30}, std::pair{1.0, 30}}) {
    rs.push_back(fixed_bed(3.0, 2, dt, steps));
    std::printf("[ fixed bed ] l = 3, fluid step %.2e s (x %d): -dp/dz = %.1f Pa/m (rel err %.2e vs Ergun)\n",
                rs.back().dt, steps, rs.back().gradient, test::rel_err(rs.back().gradient, 9733));
  }
  EXPECT_GT(rs[2].dt, 100 * 1e-5);  // well above the drag relaxation time
  for (const auto& r : rs) {
    EXPECT_TRUE(std::isfinite(r.gradient));
    EXPECT_LT(test::rel_err(r.gradient, rs[1].gradient), 1e-3);
    EXPECT_LT(test::rel_err(r.gradient, 9733), 3e-2);
  }
}
