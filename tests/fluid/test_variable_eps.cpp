// Variable void fraction: hydrostatic balance and the continuity constraint (eq. 12).
//
// 1. Hydrostatic column (closed box, gravity -y, a packed-bed-like eps: 0.4 below y = 0.5,
//    1 above, sharp or smooth tanh, with and without a large implicit drag K = 5e4 in the
//    bed): the air must stay at rest. Gravity enters as E rho g on the faces and the
//    pressure gradient as E grad p with the same E, so p = rho g.x balances it exactly:
//    spurious velocity < 1e-10 m/s after 100 steps (g T = 1 m/s), and the pressure
//    difference bottom-top equals rho g H to 1e-8 relative.
// 2. 1-D manufactured eps(x, t) = 0.6 + 0.2 sin(pi x) sin(w t) in a pipe closed at x = 0 and
//    open at x = 1 (p = 0): continuity gives the exact flux
//      (eps u)(x, t) = -int_0^x d(eps)/dt = -0.2 w cos(w t) (1 - cos(pi x)) / pi.
//    Criteria: residual |d(eps)/dt + div(E u)| < 1e-9 (relative to max|d(eps)/dt|) every
//    step, and the face flux E u against the exact flux at t^{n+1/2}: max error < 1e-3
//    relative (midpoint quadrature O(dx^2) on 32 cells).
// 3. 2-D periodic eps(x, y, t) = 0.7 + 0.2 sin(2 pi x) sin(2 pi y) cos(w t) with an initial
//    vortex: residual < 1e-9 relative every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace cgdem::fluid::test {
namespace {

void hydrostatic(bool sharp, double K) {
  MacGrid g{8, 32, 1, 1.0 / 32, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = 1.8e-5;
  p.gravity = {0, -9.81, 0};
  p.bc = uniform_boundary(BcType::Wall);
  p.bc[4].type = p.bc[5].type = BcType::Periodic;
  p.pressure.rel_tol = 1e-12;
  p.dt_max = 1e-3;
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  auto eps = [&](const Vec3& x) { return sharp ? (x.y < 0.5 ? 0.4 : 1.0) : 0.7 - 0.3 * std::tanh((0.5 - x.y) / 0.05); };
  set_cells(g, s.eps, eps);
  s.eps_old = s.eps;
  Sources src;
  if (K > 0)
    for (int d = 0; d < 3; ++d) {
      src.K[d] = make_face_field(g, d);
      set_faces(g, src.K[d], d, [&](const Vec3& x) { return x.y < 0.5 ? K : 0.0; });
    }
  geometry::Scene scene;
  for (int q = 0; q < 100; ++q) solver.advance(s, scene.at(s.t + 1e-3), src, 1e-3);
  double umax = 0;
  for (int d = 0; d < 2; ++d) {
    const Field& f = s.vel(d);
    for (int j = 0; j < f.nj(); ++j)
      for (int i = 0; i < f.ni(); ++i) umax = std::max(umax, std::fabs(f(i, j, 0)));
  }
  double dp = s.p(3, 0, 0) - s.p(3, 31, 0), dp_exact = p.rho * 9.81 * 31 * g.dx;
  std::printf("[ error ] hydrostatic (%s eps, K = %g): max |u| = %.3e m/s (tol 1e-10), dp rel. error %.2e (tol 1e-8)\n",
              sharp ? "sharp" : "smooth", K, umax, std::fabs(dp - dp_exact) / dp_exact);
  EXPECT_LT(umax, 1e-10);
  EXPECT_LT(std::fabs(dp - dp_exact) / dp_exact, 1e-8);
}

TEST(VariableEps, HydrostaticColumnStaysAtRest) {
  hydrostatic(true, 0);
  hydrostatic(false, 0);
  hydrostatic(true, 5e4);
}

TEST(VariableEps, ManufacturedContinuity1D) {
  const int n = 32;
  const double w = 20.0, dt = 2e-3;
  MacGrid g{n, 1, 1, 1.0 / n, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = 1.8e-5;
  p.bc = uniform_boundary(BcType::Periodic);
  p.bc[0].type = BcType::Wall;
  p.bc[1].type = BcType::Open;
  p.pressure.rel_tol = 1e-12;
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  auto eps = [&](double t) { return [=](const Vec3& x) { return 0.6 + 0.2 * std::sin(M_PI * x.x) * std::sin(w * t); }; };
  set_cells(g, s.eps, eps(0));
  s.eps_old = s.eps;
  geometry::Scene scene;
  double worst_res = 0, worst_flux = 0;
  const double flux_scale = 0.2 * w * 2 / M_PI, rate_scale = 0.2 * w;
  for (int q = 0; q < 100; ++q) {
    set_cells(g, s.eps, eps(s.t + dt));
    double t_half = s.t + 0.5 * dt;
    StepStats st = solver.advance(s, scene.at(s.t + dt), {}, dt);
    worst_res = std::max(worst_res, st.max_divergence / rate_scale);
    for (int i = 0; i <= n; ++i) {
      double E = i == n ? s.eps(n - 1, 0, 0) : (i == 0 ? s.eps(0, 0, 0) : 0.5 * (s.eps(i, 0, 0) + s.eps(i - 1, 0, 0)));
      double x = i * g.dx, exact = -0.2 * w * std::cos(w * t_half) * (1 - std::cos(M_PI * x)) / M_PI;
      worst_flux = std::max(worst_flux, std::fabs(E * s.u(i, 0, 0) - exact) / flux_scale);
    }
  }
  std::printf("[ error ] 1-D eps(x,t): max continuity residual %.2e (tol 1e-9), max flux error %.2e (tol 1e-3)\n",
              worst_res, worst_flux);
  EXPECT_LT(worst_res, 1e-9);
  EXPECT_LT(worst_flux, 1e-3);
}

TEST(VariableEps, ManufacturedContinuity2DPeriodic) {
  const int n = 32;
  const double w = 10.0;
  MacGrid g{n, n, 1, 1.0 / n, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = 1e-3;
  p.bc = uniform_boundary(BcType::Periodic);
  p.pressure.rel_tol = 1e-12;
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  auto eps = [&](double t) {
    return [=](const Vec3& x) { return 0.7 + 0.2 * std::sin(2 * M_PI * x.x) * std::sin(2 * M_PI * x.y) * std::cos(w * t); };
  };
  set_cells(g, s.eps, eps(0));
  s.eps_old = s.eps;
  set_faces(g, s.u, 0, [](const Vec3& x) { return std::sin(2 * M_PI * x.x) * std::cos(2 * M_PI * x.y); });
  set_faces(g, s.v, 1, [](const Vec3& x) { return -std::cos(2 * M_PI * x.x) * std::sin(2 * M_PI * x.y); });
  geometry::Scene scene;
  double worst = 0;
  int iters = 0;
  for (int q = 0; q < 60; ++q) {
    double dt = solver.stable_dt(s);
    set_cells(g, s.eps, eps(s.t + dt));
    StepStats st = solver.advance(s, scene.at(s.t + dt), {}, dt);
    worst = std::max(worst, st.max_divergence / (0.2 * w));
    iters += st.pressure_iterations;
  }
  std::printf("[ error ] 2-D periodic eps(x,y,t): max continuity residual %.2e (tol 1e-9), %.1f pressure its/step\n",
              worst, iters / 60.0);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace cgdem::fluid::test
