// The single-precision V-cycle (stencil32.hpp) against the double one, and the W-cycle against
// its double twin: the same operator up to float rounding, nearly symmetric, and independent of
// the units of the coefficients (the power-of-two scaling). Reference: the double cycle of
// multigrid.hpp applied to the same r.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "mms.hpp"
#include "solvers/pressure/multigrid.hpp"

using namespace cgdem::pressure;
using B = Boundary;
using Mg = MultigridPreconditioner;

namespace {
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}
double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, m = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i])), m = std::max(m, std::abs(b[i]));
  return d / m;
}

// coef_scale multiplies every face coefficient (units): the float V-cycle must not care.
// nu, cycle, omega: the smoothing sweeps, the cycle and the smoother's relaxation of both.
void compare(const char* name, std::array<B, 6> bc, int nx, int ny, int nz, double coef_scale, int nu = 2,
             Mg::Cycle cycle = Mg::Cycle::V, double omega = 1.0) {
  test::Problem p = test::make_problem(nx, ny, nz, bc);
  for (auto* a : {&p.ax, &p.ay, &p.az})
    for (double& v : *a) v *= coef_scale;
  for (long f = 0; f < long(p.ax.size()); f += 7) p.ax[f] = 0;  // blocked faces (solids)
  Poisson7 op(p.g);
  op.set(p.ax, p.ay, p.az);
  Mg s(p.g, nu, Mg::Precision::Single, cycle, omega), d(p.g, nu, Mg::Precision::Double, cycle, omega);
  s.setup(op);
  d.setup(op);
  ASSERT_GT(s.levels(), cycle == Mg::Cycle::W ? 2 : 1);  // a W-cycle differs from a V-cycle on 3 levels
  const long n = op.n();
  auto r = test::noise(n, 12345), q = test::noise(n, 777);
  std::vector<double> zs(n), zd(n), ws(n);
  s.apply(r.data(), zs.data());
  d.apply(r.data(), zd.data());
  s.apply(q.data(), ws.data());
  const double diff = rel_diff(zs, zd);
  // symmetry of the float operator: (M^-1 r, q) = (r, M^-1 q) up to rounding
  const double asym = std::abs(dot(zs, q) - dot(r, ws)) / std::sqrt(dot(zs, r) * dot(ws, q));
  std::printf("[ mixed ] %-9s %dx%dx%d scale %.0e: levels %d, float vs double %c(%d,%d)-cycle, omega %.2f: %.2e "
              "(tol 2e-6), asymmetry %.2e (tol 1e-7)\n", name, nx, ny, nz, coef_scale, s.levels(),
              cycle == Mg::Cycle::W ? 'W' : 'V', nu, nu, omega, diff, asym);
  EXPECT_LT(diff, 2e-6);  // float rounding (6e-8) through a few smoothing sweeps
  EXPECT_LT(asym, 1e-7);
}
}  // namespace

TEST(PressureMixedPrecision, SameVcycleAsDouble) {
  compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 32, 24, 20, 1.0);
  compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 31, 23, 19, 1e-30);
  compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 32, 24, 20, 1e30);
  compare("periodic", {B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Open, B::Open}, 32, 24, 20, 1.0);
  compare("periodic", {B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic}, 24, 24, 24, 1.0);
}

// The W-cycle, plain and over-relaxed as in "pcg-mgw3" (omega 1.2): the same checks on grids of
// three and (96x64x48) four levels; the over-relaxed V-cycle on the grids above.
TEST(PressureMixedPrecision, WcycleAndOverRelaxationAsDouble) {
  const auto W = Mg::Cycle::W;
  for (double omega : {1.0, 1.2}) {
    compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 96, 64, 48, 1.0, 3, W, omega);
    compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 47, 39, 33, 1e-30, 3, W, omega);
    compare("periodic", {B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Open, B::Open}, 64, 48, 40, 1.0, 3, W,
            omega);
  }
  compare("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}, 31, 23, 19, 1e30, 2, Mg::Cycle::V, 1.2);
  compare("periodic", {B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic}, 24, 24, 24, 1.0,
          2, Mg::Cycle::V, 1.2);
}
