// The stripped reference of the DEM law (bench/dem/stripped_dem.hpp) integrates the same
// system as the engine: a compressed lattice in a walled box, spinning and moving at
// random, stepped by both from the engine's state after its first step. Positions and
// velocities must agree to round-off (the reference fuses multiply-adds and sums in
// another order), so its speed is a bound for the same physics, not for less of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "bench/dem/stripped_dem.hpp"

namespace cgdem::bench {
namespace {

void follows_the_engine(bool accounts) {
  const double d = 375e-6, r = d / 2;
  const int nx = 6, ny = 5, nz = 8;
  const double a = 0.998 * d;  // lattice spacing: every neighbour and wall overlaps a little
  const double lx = (nx - 1) * a + 2 * r * 0.998, ly = (ny - 1) * a + 2 * r * 0.998;
  const std::vector<Plane> planes{{{0, 0, 0}, {1, 0, 0}}, {{lx, 0, 0}, {-1, 0, 0}}, {{0, 0, 0}, {0, 1, 0}},
                                  {{0, ly, 0}, {0, -1, 0}}, {{0, 0, 0}, {0, 0, 1}}};
  geometry::Scene scene;
  const int box = scene.add_body("box", geometry::Motion{});
  for (const Plane& pl : planes) scene.add_part(box, "wall", geometry::make_half_space(pl.point, pl.normal));
  Species s{"bed", d, 1.0, 1500.0};
  DemParams prm;
  prm.dt = 1e-6;
  prm.skin = 0.5 * d;
  prm.domain = {{-0.01, -0.01, -0.01}, {0.02, 0.02, 0.1}};
  DemSolver dem({s}, MaterialParams{50.0, 0.9, 0.3, 0.9, 0.3}, prm, scene);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int64_t id = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        dem.particles().add(id++, 0, s, {0.998 * r + i * a, 0.998 * r + j * a, 0.998 * r + k * a},
                            {0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng)}, {300 * u(rng), 300 * u(rng), 300 * u(rng)});
  dem.step();
  const EnergyBudget e0 = dem.energy();
  StrippedDem ref(dem, planes, accounts);
  const int steps = 400;
  for (int k = 0; k < steps; ++k) {
    dem.step();
    ref.step();
  }
  ASSERT_EQ(dem.neighbor_builds(), 1) << "the engine rebuilt its lists; the reference cannot follow";
  const Particles& p = dem.particles();
  double dx = 0, dv = 0, dw = 0, vmax = 0, wmax = 0;
  for (int i = 0; i < ref.size(); ++i) {
    dx = std::max(dx, norm(p.x[i] - ref.position(i)));
    dv = std::max(dv, norm(p.v[i] - ref.velocity(i)));
    dw = std::max(dw, norm(p.omega[i] - ref.angular_velocity(i)));
    vmax = std::max(vmax, norm(p.v[i]));
    wmax = std::max(wmax, norm(p.omega[i]));
  }
  const EnergyBudget e = dem.energy();
  std::printf("after %d steps: max |dx| %.3g m (of d: %.3g), max |dv| %.3g of max |v| %.3g m/s, max |dw| %.3g of "
              "max |w| %.3g 1/s; engine dissipated by friction %.3g J, E_kin engine %.17g reference %.17g\n",
              steps, dx, dx / d, dv / vmax, vmax, dw / wmax, wmax, e.dissipated_friction,
              e.kinetic_translational + e.kinetic_rotational, ref.kinetic_energy());
  EXPECT_GT(e.dissipated_friction, 0.0);  // the tangential law is exercised
  EXPECT_LT(dx / d, 1e-10);
  EXPECT_LT(dv / vmax, 1e-8);
  EXPECT_LT(dw / wmax, 1e-8);
  if (accounts) {
    // The reference takes over the engine's accounts after its first step; what both
    // booked since is compared.
    const double damp = ref.dissipated_damping() - e0.dissipated_damping;
    const double fric = ref.dissipated_friction() - e0.dissipated_friction;
    const double damp_err = std::fabs(e.dissipated_damping - e0.dissipated_damping - damp) / damp;
    const double fric_err = std::fabs(e.dissipated_friction - e0.dissipated_friction - fric) / fric;
    std::printf("dissipated in %d steps: damping %.6g J (relative difference %.2g), friction %.6g J (%.2g)\n", steps,
                damp, damp_err, fric, fric_err);
    EXPECT_LT(damp_err, 1e-9);
    EXPECT_LT(fric_err, 1e-9);
  } else {
    EXPECT_EQ(ref.dissipated_damping(), 0.0);
    EXPECT_EQ(ref.dissipated_friction(), 0.0);
  }
}

TEST(StrippedDem, FollowsTheEngineToRoundOff) { follows_the_engine(false); }
TEST(StrippedDem, WithAccountsBooksWhatTheEngineBooks) { follows_the_engine(true); }

}  // namespace
}  // namespace cgdem::bench
