// Lid-driven cavity, unit square, lid speed 1 (the +y side is a Wall with U_w = (1, 0, 0)),
// 2-D in a one-cell periodic slab. Steady centreline velocities against Ghia, Ghia & Shin
// (1982) (docs/references.md, Lid-driven cavity). Max deviation over the tabulated points,
// in units of the lid speed:
//   CI:   Re = 100 on 32^2: < 2 % as well (measured 0.67 %; the coarse grid already meets it)
//         Re = 400 on 32^2: < 5 % (measured 3.49 %; the thinner boundary layers need a finer
//         grid: 64^2 gives 0.67 % but costs ~20 s of CPU, too slow for CI)
//   full (CGDEM_FULL_VALIDATION=1): Re = 100 and Re = 400 on 128^2: < 2 % (measured values
//         in validation/air/lid_cavity/README.md).
// The centreline profiles are interpolated to Ghia's points with 3-point Lagrange polynomials.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "fluid_test_util.hpp"

namespace cgdem::fluid::test {
namespace {

constexpr int kRe400CiGrid = 32;
constexpr double kRe400CiTol = 0.05;

struct Ref {
  double pos, re100, re400;
};
// u(y) on x = 0.5 and v(x) on y = 0.5; Ghia's row at x = 0.9063 for Re = 400 is marked as
// inconsistent in docs/references.md and is skipped for Re = 400 (NaN).
const std::vector<Ref> kGhiaU = {
    {0.9766, 0.84123, 0.75837},  {0.9688, 0.78871, 0.68439},   {0.9609, 0.73722, 0.61756},
    {0.9531, 0.68717, 0.55892},  {0.8516, 0.23151, 0.29093},   {0.7344, 0.00332, 0.16256},
    {0.6172, -0.13641, 0.02135}, {0.5000, -0.20581, -0.11477}, {0.4531, -0.21090, -0.17119},
    {0.2813, -0.15662, -0.32726}, {0.1719, -0.10150, -0.24299}, {0.1016, -0.06434, -0.14612},
    {0.0703, -0.04775, -0.10338}, {0.0625, -0.04192, -0.09266}, {0.0547, -0.03717, -0.08186}};
const std::vector<Ref> kGhiaV = {
    {0.9688, -0.05906, -0.12146}, {0.9609, -0.07391, -0.15663}, {0.9531, -0.08864, -0.19254},
    {0.9453, -0.10313, -0.22847}, {0.9063, -0.16914, NAN},      {0.8594, -0.22445, -0.44993},
    {0.8047, -0.24533, -0.38598}, {0.5000, 0.05454, 0.05186},   {0.2344, 0.17527, 0.30174},
    {0.2266, 0.17507, 0.30203},   {0.1563, 0.16077, 0.28124},   {0.0938, 0.12317, 0.22965},
    {0.0781, 0.10890, 0.20920},   {0.0703, 0.10091, 0.19713},   {0.0625, 0.09233, 0.18360}};

// 3-point Lagrange interpolation of samples (xs, ys) at x (xs increasing).
double interp(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  size_t i = 1;
  while (i + 1 < xs.size() - 1 && xs[i] < x) ++i;
  double x0 = xs[i - 1], x1 = xs[i], x2 = xs[i + 1];
  return ys[i - 1] * (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2)) +
         ys[i] * (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2)) + ys[i + 1] * (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1));
}

double cavity_deviation(int n, double re) {
  MacGrid g{n, n, 1, 1.0 / n, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.0;
  p.mu = 1.0 / re;
  p.bc = uniform_boundary(BcType::Wall);
  p.bc[4].type = p.bc[5].type = BcType::Periodic;
  p.bc[3].wall_velocity = {1, 0, 0};
  p.pressure.rel_tol = 1e-9;
  FluidSolver solver(g, p);
  FluidState s = make_fluid_state(g);
  geometry::Scene scene;
  // March to steady state: max |du/dt| < 1e-4 (lid speed / time unit), checked every 50 steps.
  const double t_max = re > 200 ? 60.0 : 30.0;
  Field u_prev = s.u;
  int steps = 0, iters = 0;
  double change = 1;
  while (s.t < t_max) {
    double t0 = s.t;
    for (int q = 0; q < 50; ++q) iters += solver.advance(s, scene.at(s.t), {}, solver.stable_dt(s)).pressure_iterations;
    steps += 50;
    change = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i <= n; ++i) change = std::max(change, std::fabs(s.u(i, j, 0) - u_prev(i, j, 0)));
    change /= (s.t - t0);
    u_prev = s.u;
    if (change < 1e-4) break;
  }
  // Centreline samples, with the wall values at the ends.
  std::vector<double> ys{0}, us{0}, xs{0}, vs{0};
  for (int j = 0; j < n; ++j) ys.push_back((j + 0.5) / n), us.push_back(s.u(n / 2, j, 0));
  for (int i = 0; i < n; ++i) xs.push_back((i + 0.5) / n), vs.push_back(s.v(i, n / 2, 0));
  ys.push_back(1), us.push_back(1), xs.push_back(1), vs.push_back(0);
  double dev = 0;
  for (const Ref& r : kGhiaU) dev = std::max(dev, std::fabs(interp(ys, us, r.pos) - (re > 200 ? r.re400 : r.re100)));
  for (const Ref& r : kGhiaV) {
    double ref = re > 200 ? r.re400 : r.re100;
    if (!std::isnan(ref)) dev = std::max(dev, std::fabs(interp(xs, vs, r.pos) - ref));
  }
  std::printf("[ cavity Re=%g %dx%d ] t = %.1f, %d steps, mean pressure iterations %.1f, |du/dt| = %.1e\n", re, n, n,
              s.t, steps, double(iters) / (2 * steps), change);
  std::printf("%s", solver.timers().table("cavity per-phase time").c_str());
  return dev;
}

TEST(LidCavity, Re100CoarseCI) {
  double dev = cavity_deviation(32, 100);
  std::printf("[ error ] Re=100 32x32: max |u - u_Ghia| on the centrelines = %.4f (tol 0.02)\n", dev);
  EXPECT_LT(dev, 0.02);
}

// Re = 400 needs a finer grid than Re = 100 for the same accuracy; the CI variant uses 32^2
// with the looser tolerance stated in the file header (measured value there).
TEST(LidCavity, Re400CoarseCI) {
  double dev = cavity_deviation(kRe400CiGrid, 400);
  std::printf("[ error ] Re=400 %dx%d: max |u - u_Ghia| on the centrelines = %.4f (tol %.2f)\n", kRe400CiGrid,
              kRe400CiGrid, dev, kRe400CiTol);
  EXPECT_LT(dev, kRe400CiTol);
}

TEST(LidCavity, Full128Re100) {
  if (!full_validation()) GTEST_SKIP() << "set CGDEM_FULL_VALIDATION=1 for the 128x128 runs";
  double dev = cavity_deviation(128, 100);
  std::printf("[ error ] Re=100 128x128: max deviation from Ghia = %.4f (tol 0.02)\n", dev);
  EXPECT_LT(dev, 0.02);
}

TEST(LidCavity, Full128Re400) {
  if (!full_validation()) GTEST_SKIP() << "set CGDEM_FULL_VALIDATION=1 for the 128x128 runs";
  double dev = cavity_deviation(128, 400);
  std::printf("[ error ] Re=400 128x128: max deviation from Ghia = %.4f (tol 0.02)\n", dev);
  EXPECT_LT(dev, 0.02);
}

}  // namespace
}  // namespace cgdem::fluid::test
