// Open (fixed-pressure) sides and the implicit momentum source K.
//
// 1. Pressure-driven channel: Open sides at x = 0 (p = P) and x = L (p = 0), walls at y = 0, 1
//    (domain walls, not IBM), periodic z. Exact: u = G/(2 mu) y (1 - y), G = P/L, and
//    p linear in x. Criterion: rms error / u_max < 1e-2 on ny = 16 and observed order
//    >= 1.8 from 16 to 32; pressure at cell centres linear to 1e-8 relative.
// 2. Semi-implicit drag: periodic box, eps = 0.4, gravity g_x, uniform K (the packed-bed beta
//    of docs/model.md, Stability: 5e4 kg m^-3 s^-1), Kv = 0. The air relaxation time eps rho/K = 8e-6 s is
//    far below dt = 1e-3 s; steady state eps rho g = K u, i.e. u = eps rho g/K.
//    Criterion: stable, relative error < 1e-10 after 20 steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace cgdem::fluid::test {
namespace {

double channel_error(int ny, double* p_err) {
  const double L = 0.5, P = 4.0, mu = 1.0, G = P / L;
  MacGrid g{ny / 2, ny, 1, 1.0 / ny, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = mu;
  p.bc = uniform_boundary(BcType::Periodic);
  p.bc[0].type = p.bc[1].type = BcType::Open;
  p.bc[0].pressure = P;
  p.bc[1].pressure = 0.0;
  p.bc[2].type = p.bc[3].type = BcType::Wall;
  p.time_order = 1;
  p.pressure.rel_tol = 1e-12;
  auto exact = [&](const Vec3& x) { return G / (2 * mu) * x.y * (1 - x.y); };
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  geometry::Scene scene;
  const double dt = solver.stable_dt(s);
  const int steps = static_cast<int>(std::ceil(10.0 / (M_PI * M_PI * mu) / dt));  // 10 decay times
  for (int q = 0; q < steps; ++q) solver.advance(s, scene.at(s.t + dt), {}, dt);
  const double umax = G / (8 * mu);
  Norms e = face_error(g, s.u, 0, exact);
  double pe = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < g.nx; ++i) pe = std::max(pe, std::fabs(s.p(i, j, 0) - P * (1 - (i + 0.5) * g.dx / L)) / P);
  *p_err = pe;
  std::printf("[ open channel ny = %d ] %d steps, rms error/u_max %.3e, pressure error %.1e\n", ny, steps, e.rms / umax, pe);
  return e.rms / umax;
}

TEST(OpenBoundary, PressureDrivenChannel) {
  double pe16, pe32;
  double e16 = channel_error(16, &pe16), e32 = channel_error(32, &pe32);
  std::printf("[ error ] open channel rms/u_max %.3e (16), %.3e (32), order %.2f (tol < 1e-2, >= 1.8); "
              "p error %.1e (tol 1e-8)\n", e16, e32, order(e16, e32), std::max(pe16, pe32));
  EXPECT_LT(e16, 1e-2);
  EXPECT_GE(order(e16, e32), 1.8);
  EXPECT_LT(std::max(pe16, pe32), 1e-8);
}

TEST(ImplicitDrag, PackedBedDarcyBalance) {
  MacGrid g{8, 8, 1, 1e-3, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = 1.8e-5;
  p.gravity = {9.81, 0, 0};
  p.bc = uniform_boundary(BcType::Periodic);
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  s.eps.fill(0.4);
  s.eps_old.fill(0.4);
  const double K = 5e4;
  Sources src;
  for (int d = 0; d < 3; ++d) src.K[d] = make_face_field(g, d, K);
  geometry::Scene scene;
  for (int q = 0; q < 20; ++q) solver.advance(s, scene.at(s.t + 1e-3), src, 1e-3);
  const double u_exact = 0.4 * 1.0 * 9.81 / K;
  Norms e = face_error(g, s.u, 0, [&](const Vec3&) { return u_exact; });
  std::printf("[ error ] implicit drag: u = %.6e m/s, exact eps rho g/K = %.6e, rel. error %.2e (tol 1e-10)\n",
              s.u(3, 3, 0), u_exact, e.max / u_exact);
  EXPECT_LT(e.max / u_exact, 1e-10);
}

}  // namespace
}  // namespace cgdem::fluid::test
