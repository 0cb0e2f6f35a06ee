// Taylor-Green vortex, 2-D periodic (thin 3-D slab, one cell in z), against the exact
// solution of docs/references.md (Taylor-Green vortex):
//   u = sin x cos y F,  v = -cos x sin y F,  F = exp(-2 nu t),  KE(t) = KE(0) F^2.
// Observed spatial order of the velocity error over three grids (dt = CFL dx, Heun in time,
// so the combined error is O(dx^2) when the scheme is second order).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace cgdem::fluid::test {
namespace {

struct TgResult {
  double err_rms, ke_rel_err, max_div;
  int steps;
};

TgResult run_tg(int n, double nu, double t_end, Advection adv) {
  const double L = 2 * M_PI;
  MacGrid g{n, n, 1, L / n, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = nu;
  p.bc = uniform_boundary(BcType::Periodic);
  p.advection = adv;
  p.pressure.rel_tol = 1e-11;
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  set_faces(g, s.u, 0, [](const Vec3& x) { return std::sin(x.x) * std::cos(x.y); });
  set_faces(g, s.v, 1, [](const Vec3& x) { return -std::cos(x.x) * std::sin(x.y); });
  const double ke0 = kinetic_energy_2d(s);
  geometry::Scene scene;
  double max_div = 0;
  int steps = run_to(solver, s, scene, t_end, [&](const StepStats& st) { max_div = std::max(max_div, st.max_divergence); });
  const double F = std::exp(-2 * nu * t_end);
  Norms eu = face_error(g, s.u, 0, [&](const Vec3& x) { return std::sin(x.x) * std::cos(x.y) * F; });
  Norms ev = face_error(g, s.v, 1, [&](const Vec3& x) { return -std::cos(x.x) * std::sin(x.y) * F; });
  double ke_exact = ke0 * F * F;
  if (n == 64) std::printf("%s", solver.timers().table("TG 64^2 per-phase time").c_str());
  return {std::sqrt(0.5 * (eu.rms * eu.rms + ev.rms * ev.rms)), std::fabs(kinetic_energy_2d(s) - ke_exact) / ke_exact,
          max_div, steps};
}

TEST(TaylorGreen, SpatialOrderAndEnergyDecay) {
  const double nu = 0.05, t_end = 1.0;
  const int grids[3] = {16, 32, 64};
  for (Advection adv : {Advection::VanLeer, Advection::MC}) {
    TgResult r[3];
    for (int q = 0; q < 3; ++q) {
      r[q] = run_tg(grids[q], nu, t_end, adv);
      std::printf("[ TG %s ] n = %3d  steps %4d  rms error %.3e  KE rel. error %.3e  max div %.1e\n",
                  adv == Advection::VanLeer ? "van-leer" : "mc", grids[q], r[q].steps, r[q].err_rms,
                  r[q].ke_rel_err, r[q].max_div);
    }
    double o1 = order(r[0].err_rms, r[1].err_rms), o2 = order(r[1].err_rms, r[2].err_rms);
    std::printf("[ error ] observed order %.2f (16->32), %.2f (32->64)  (tol >= 1.8)\n", o1, o2);
    EXPECT_GE(o2, 1.8);
    EXPECT_GE(o1, 1.8);
    std::printf("[ error ] KE relative error on 64^2: %.3e (tol 1e-2)\n", r[2].ke_rel_err);
    EXPECT_LT(r[2].ke_rel_err, 1e-2);
    EXPECT_LT(r[2].max_div, 1e-7);
  }
}

}  // namespace
}  // namespace cgdem::fluid::test
