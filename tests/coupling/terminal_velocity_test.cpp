// A single parcel falling through still air reaches the terminal velocity of ONE original
// particle, 0.520 m/s for d_O = 125 um (docs/references.md, Terminal velocity), whatever its ratio l = 1,
// 2, 3: the drag uses d_O and scales with the parcel volume like its weight. A "simply
// large" particle (l = 1, d_O = 375 um) falls four times faster (2.11 m/s).
//
// Set-up: periodic in z (the fall is 0.2 m long), walls in x and y, one-way coupling
// (feedback off: a lone parcel in a cell would otherwise drag the air with it at a speed
// that depends on the cell size, not on the drag law), air gravity off (no hydrostatic
// pressure in a periodic column; buoyancy is 0.07 % of the weight). Grid 2 mm (dx/d >= 5),
// so the parcel's own volume lowers eps at its centre by < 0.5 %.
#include <gtest/gtest.h>

#include "coupled_util.hpp"

using namespace cgdem;

namespace {

double fall(double ratio, double d_o, double t_end) {
  test::SystemSpec s;
  s.grid = test::make_grid(4, 4, 8, 2e-3);
  s.air.bc = fluid::uniform_boundary(fluid::BcType::Wall);
  s.air.bc[4].type = s.air.bc[5].type = fluid::BcType::Periodic;
  s.air.pressure.method = "pcg-fft";
  s.species = {{"powder", d_o, ratio, 1500}};
  s.dem.dt = 1e-5;  // no contacts: only the drag relaxation time (> 50 ms) limits it
  s.dem.gravity = {0, 0, -9.81};
  s.coupled.dt_fluid_max = 5e-4;
  s.coupled.feedback = false;
  auto sys = test::make_system(s, [&](Particles& p) { p.add(0, 0, s.species[0], {4e-3, 4e-3, 8e-3}); });
  while (sys->cs->time() < t_end - 1e-12) sys->cs->step();
  return -sys->dem->particles().v[0].z;
}

}  // namespace

TEST(TerminalVelocity, SameForEveryRatioWithTheOriginalDiameter) {
  const double want = 0.520;
  double worst = 0;
  for (double l : {1.0, 2.0, 3.0}) {
    const double v = fall(l, 125e-6, 0.45);  // 8.5 relaxation times (tau = 53 ms)
    const double err = test::rel_err(v, want);
    worst = std::max(worst, err);
    std::printf("[ terminal ] l = %.0f: %.4f m/s after 0.45 s (0.520; rel err %.2e, tol 2e-2)\n", l, v, err);
  }
  EXPECT_LT(worst, 2e-2);
}

TEST(TerminalVelocity, SimplyLargeParticleFallsFaster) {
  const double v = fall(1.0, 375e-6, 1.2);  // tau ~ 0.2 s
  std::printf("[ terminal ] simply large (l = 1, 375 um): %.3f m/s (2.11; rel err %.2e, tol 2e-2)\n", v,
              test::rel_err(v, 2.11));
  EXPECT_LT(test::rel_err(v, 2.11), 2e-2);
}
