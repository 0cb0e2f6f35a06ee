// The implicit drag coupling (solvers/coupled/implicit_drag.hpp) against closed forms.
//
// 1. The KINSOL driver alone on u = cos(u) per component (root 0.739085133215161), both
//    methods: converged to the tolerance, the iteration counts printed; and the error after
//    k iterations: quadratic for Newton, super-linear for Anderson.
// 2. One step of air through a fixed, uniform packed bed (periodic box, parcels at rest on
//    a lattice that maps eps = 0.4 exactly, Ergun branch, d_O = 125 um). With no pressure
//    gradient, advection or shear the x-face equation of the step is scalar:
//        (eps rho/dt)(u - U0) = -(1 - eps)(A + B u) u,
//        A = 150 mu (1-eps)/(eps d_O^2),  B = 1.75 rho/d_O   (beta/(1-eps), eq. 9)
//    The implicit step must return its positive root (a quadratic) to the nonlinear
//    tolerance; the semi-implicit step, A + B U0 instead of A + B u, must not.
// 3. The same bed over many steps: eps rho du/dt = -(1-eps)(A + B u) u has the closed form
//        u(t) = a U0 e^{-a t} / (a + b U0 (1 - e^{-a t})),  a = (1-eps)A/(eps rho),
//                                                          b = (1-eps)B/(eps rho)
//    (a manufactured solution of the coupled nonlinear system); the implicit coupling must
//    converge to it at first order in dt (backward Euler in the drag), observed order printed.
// 4. Air through a fixed packed bed in the Forchheimer regime (Re_p = rho d_O U/mu = 10,
//    where Ergun's inertial term is 16 % of the pressure gradient): -dp/dz against Ergun
//    within 2 % at fluid steps 1e-5 s, 1e-4 s and the largest the CFL limit allows.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupled_util.hpp"
#include "solvers/coupled/implicit_drag.hpp"

using namespace cgdem;

namespace {

constexpr double kDo = 125e-6, kMu = 1.8e-5, kRho = 1.0, kEps = 0.4;
constexpr double kA = 150 * kMu * (1 - kEps) / (kEps * kDo * kDo);  // [kg m^-3 s^-1]
constexpr double kB = 1.75 * kRho / kDo;                              // [kg m^-4]

std::string history(const ImplicitDragStats& s) {
  std::string h;
  for (double r : s.history) h += fmt::format(" {:.1e}", r);
  return h;
}

// A periodic box of 2 x 2 x 2 cells holding a fixed lattice of l = 3 parcels (2 per cell
// and axis, eps 0.4), the air at U0 along x.
std::unique_ptr<test::CoupledSystem> uniform_bed(double U0, double dt, DragCoupling coupling,
                                                 const std::string& method = "anderson") {
  const double l = 3, d = l * kDo;
  const double a = d * std::cbrt(std::numbers::pi / (6 * (1 - kEps)));
  test::SystemSpec s;
  s.grid = test::make_grid(2, 2, 2, 2 * a);
  s.air.rho = kRho, s.air.mu = kMu;
  s.air.bc = fluid::uniform_boundary(fluid::BcType::Periodic);
  s.air.pressure.method = "pcg-fft";
  s.air.pressure.rel_tol = 1e-10;
  s.air.dt_max = 1e30;
  s.species = {{"powder", kDo, l, 1500}};
  s.dem.dt = dt / 16;
  s.dem.gravity = {0, 0, 0};
  s.coupled.dt_fluid_max = dt;
  s.coupled.move_particles = false;
  s.coupled.coupling = coupling;
  s.coupled.implicit.method = method;
  s.coupled.implicit.tol = 1e-9;
  auto sys = test::make_system(s, [&](Particles& p) { test::add_cubic_lattice(p, s.species[0], 4, 4, a, 0.0); });
  sys->air.u.fill(U0);
  return sys;
}

// Mean x velocity and the spread over the x-faces.
std::pair<double, double> mean_u(const fluid::FluidState& air) {
  double m = 0, lo = 1e30, hi = -1e30;
  int n = 0;
  for (int k = 0; k < air.grid.nz; ++k)
    for (int j = 0; j < air.grid.ny; ++j)
      for (int i = 0; i < air.grid.nx; ++i) {
        m += air.u(i, j, k), ++n;
        lo = std::min(lo, air.u(i, j, k)), hi = std::max(hi, air.u(i, j, k));
      }
  return {m / n, hi - lo};
}

double closed_form_step(double U0, double dt) {
  const double qa = (1 - kEps) * kB, qb = (1 - kEps) * kA + kEps * kRho / dt, qc = -kEps * kRho * U0 / dt;
  return (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
}

double closed_form_decay(double U0, double t) {
  const double a = (1 - kEps) * kA / (kEps * kRho), b = (1 - kEps) * kB / (kEps * kRho);
  const double e = std::exp(-a * t);
  return a * U0 * e / (a + b * U0 * (1 - e));
}

}  // namespace

TEST(ImplicitDrag, KinsolFindsTheFixedPointOfCosine) {
  const double root = 0.739085133215161;
  for (const char* method : {"anderson", "newton"}) {
    ImplicitDragOptions o;
    o.method = method;
    o.tol = 1e-12;
    o.depth = 4;  // five independent components: a deep history helps (the default 1 needs ~30)
    ImplicitDragSolver solver(5, o);
    std::vector<double> u{0.0, 0.5, 1.0, 2.0, -1.0};
    const auto st = solver.solve(
        [](const double* in, double* out) {
          for (int i = 0; i < 5; ++i) out[i] = std::cos(in[i]);
        },
        u);
    double err = 0;
    for (double x : u) err = std::max(err, std::fabs(x - root));
    std::printf("[ implicit drag ] u = cos(u), %s: %d iterations, %d evaluations, residual %.2e (tol 1e-12), "
                "error %.2e; residuals:%s\n",
                method, st.iterations, st.evaluations, st.residual, err, history(st).c_str());
    EXPECT_TRUE(st.converged);
    EXPECT_LT(err, 1e-11);
    EXPECT_LT(st.evaluations, 40);  // plain iteration (rate 0.67) would need ~70
  }
}

// The order of convergence of the two methods, on u = cos(u) from u0 = 1 (error 0.26): each
// run stops after k = 1, 2, ... iterations (max_iterations = k, a tolerance no run reaches
// before the error is at round-off), and its last evaluated iterate's error against the root
// is e_k. Newton's method (Jacobian-vector products by difference quotients) must converge
// quadratically while the error is above the difference quotients' noise (1e-7):
// e_{k+1} <= e_k^2 (this map's constant is 0.22). Anderson of depth 1 is, for one unknown,
// the secant method (order 1.62); its first iteration is a plain step, whose iterate its
// second evaluation sees, so from the third on it must be super-linear: e_{k+1} <= e_k^1.3.
// Printed: the errors and the observed orders log(e_{k+1}) / log(e_k).
TEST(ImplicitDrag, NewtonConvergesQuadraticallyAndAndersonSuperlinearly) {
  const double root = 0.739085133215161;
  for (const char* method : {"newton", "anderson"}) {
    const bool newton = std::string(method) == "newton";
    std::vector<double> e;
    for (int k = 1; k <= (newton ? 4 : 6); ++k) {
      ImplicitDragOptions o;
      o.method = method;
      o.tol = 1e-300;
      o.max_iterations = k;
      ImplicitDragSolver solver(1, o);
      std::vector<double> u{1.0};
      const auto st = solver.solve([](const double* in, double* out) { out[0] = std::cos(in[0]); }, u);
      if (!st.converged) EXPECT_EQ(st.iterations, k);  // else the residual reached exactly 0
      e.push_back(std::fabs(u[0] - root));
    }
    std::string line;
    for (size_t k = 0; k < e.size(); ++k)
      line += fmt::format(" e{} = {:.2e}{}", k + 1, e[k],
                          k ? fmt::format(" (order {:.2f})", std::log(e[k]) / std::log(e[k - 1])) : std::string());
    std::printf("[ implicit drag ] u = cos(u) from 1.0, %s, error after k iterations:%s\n", method, line.c_str());
    for (size_t k = newton ? 1 : 2; k < e.size(); ++k) {
      if (e[k - 1] < 1e-7) break;  // below it the difference quotients' noise sets the error
      EXPECT_LE(e[k], std::pow(e[k - 1], newton ? 2.0 : 1.3)) << method << ", iteration " << k + 1;
    }
  }
}

TEST(ImplicitDrag, UniformBedStepIsTheRootOfItsQuadratic) {
  const double U0 = 3.6, dt = 2e-6;  // Re = eps rho d_O U0/mu = 10; eps rho/dt comparable to the drag
  const double want = closed_form_step(U0, dt);
  const double semi_want = kEps * kRho * U0 / dt / (kEps * kRho / dt + (1 - kEps) * (kA + kB * U0));
  for (const char* method : {"anderson", "newton"}) {
    auto sys = uniform_bed(U0, dt, DragCoupling::Implicit, method);
    const CoupledStepStats st = sys->cs->step();
    const auto [u, spread] = mean_u(sys->air);
    const double err = test::rel_err(u, want);
    std::printf("[ implicit drag ] uniform bed, one step of %.1e s from %.2f m/s, %s: u = %.9f m/s, closed form "
                "%.9f (rel err %.2e, tol 1e-8), spread over faces %.1e; %d iterations, %d air steps, "
                "residuals (m/s):%s\n",
                dt, U0, method, u, want, err, spread, st.drag.iterations, st.drag.evaluations,
                history(st.drag).c_str());
    EXPECT_TRUE(st.drag.converged);
    EXPECT_LT(err, 1e-8);
    EXPECT_LT(spread, 1e-10);
    EXPECT_LE(st.drag.evaluations, 12);
  }
  auto semi = uniform_bed(U0, dt, DragCoupling::SemiImplicit);
  semi->cs->step();
  const double us = mean_u(semi->air).first;
  std::printf("[ implicit drag ] the same step semi-implicit: u = %.9f m/s (its own closed form %.9f, rel err %.2e); "
              "%.2f %% from the implicit root\n",
              us, semi_want, test::rel_err(us, semi_want), 100 * (us / want - 1));
  EXPECT_LT(test::rel_err(us, semi_want), 1e-8);
  EXPECT_GT(test::rel_err(us, want), 1e-2);  // the nonlinearity is not negligible in this test
}

TEST(ImplicitDrag, DecayThroughAFixedBedConvergesAtFirstOrder) {
  const double U0 = 3.6, T = 8e-6;
  const double want = closed_form_decay(U0, T);
  std::vector<double> errs;
  for (double dt : {2e-6, 1e-6, 5e-7, 2.5e-7}) {
    auto sys = uniform_bed(U0, dt, DragCoupling::Implicit);
    int iters = 0, steps = 0;
    while (sys->cs->time() < T - 1e-15) {
      const auto st = sys->cs->step();
      EXPECT_TRUE(st.drag.converged);
      iters += st.drag.iterations, ++steps;
    }
    errs.push_back(std::fabs(mean_u(sys->air).first - want) / want);
    std::printf("[ implicit drag ] decay to t = %.1e s at dt %.2e s (%d steps, %.1f iterations per step): u = %.6e "
                "m/s, closed form %.6e, rel err %.3e%s\n",
                T, dt, steps, double(iters) / steps, mean_u(sys->air).first, want, errs.back(),
                errs.size() > 1 ? fmt::format(", observed order {:.3f}", std::log2(errs[errs.size() - 2] / errs.back())).c_str()
                                : "");
  }
  for (size_t i = 1; i < errs.size(); ++i) {
    const double order = std::log2(errs[i - 1] / errs[i]);
    EXPECT_GT(order, 0.85);
    EXPECT_LT(order, 1.15);
  }
}

namespace {

// The fixed bed of fixed_bed_test.cpp (l = 3, eps 0.4 exactly, 8 cells high between two
// empty regions), air entering at the bottom at superficial velocity U.
double forchheimer_gradient(double U, double dt_max, double cfl, int steps, DragCoupling coupling, double* dt_out,
                            double* iters_out) {
  const double ratio = 3, d = ratio * kDo;
  const double a = d * std::cbrt(std::numbers::pi / (6 * 0.6));
  const int per_cell = 2, nxy = 2, nz = 16, bed0 = 4, bed1 = 12;
  const double dx = per_cell * a;
  test::SystemSpec s;
  s.grid = test::make_grid(nxy, nxy, nz, dx);
  s.air.rho = kRho, s.air.mu = kMu;
  s.air.bc = fluid::uniform_boundary(fluid::BcType::Periodic);
  s.air.bc[4] = {fluid::BcType::Wall, Vec3{0, 0, U}, 0};
  s.air.bc[5] = {fluid::BcType::Open, Vec3{}, 0};
  s.air.pressure.method = "pcg-fft";
  s.air.pressure.rel_tol = 1e-10;
  s.air.dt_max = 1e30;
  s.air.cfl = cfl;
  s.species = {{"powder", kDo, ratio, 1500}};
  s.dem.dt = 1e-6;
  s.dem.gravity = {0, 0, 0};
  s.coupled.dt_fluid_max = dt_max;
  s.coupled.move_particles = false;
  s.coupled.coupling = coupling;
  s.coupled.implicit.tol = 1e-8;
  auto sys = test::make_system(s, [&](Particles& p) {
    test::add_cubic_lattice(p, s.species[0], nxy * per_cell, (bed1 - bed0) * per_cell, a, bed0 * dx);
  });
  long iters = 0;
  for (int n = 0; n < steps; ++n) {
    const auto st = sys->cs->step();
    *dt_out = st.dt_fluid;
    iters += st.drag.evaluations;
    if (n == 0 && coupling == DragCoupling::Implicit)
      std::printf("[ implicit drag ] Forchheimer bed, first step from rest at %.2e s: %d iterations, %d air steps, "
                  "residuals (m/s):%s\n", st.dt_fluid, st.drag.iterations, st.drag.evaluations, history(st.drag).c_str());
  }
  *iters_out = double(iters) / steps;
  const auto& air = sys->air;
  const int k0 = bed0 + 2, k1 = bed1 - 3;
  double p0 = 0, p1 = 0;
  for (int j = 0; j < nxy; ++j)
    for (int i = 0; i < nxy; ++i) p0 += air.p(i, j, k0) / (nxy * nxy), p1 += air.p(i, j, k1) / (nxy * nxy);
  return (p0 - p1) / ((k1 - k0) * dx);
}

}  // namespace

TEST(ImplicitDrag, ForchheimerFixedBedMatchesErgunAtEveryStep) {
  const double U = 10 * kMu / (kRho * kDo);  // Re_p = rho d_O U / mu = 10: 1.44 m/s
  const double e3 = kEps * kEps * kEps;
  const double visc = 150 * kMu * (1 - kEps) * (1 - kEps) * U / (e3 * kDo * kDo);
  const double inert = 1.75 * kRho * (1 - kEps) * U * U / (e3 * kDo);
  const double want = visc + inert;
  std::printf("[ implicit drag ] Forchheimer bed: U = %.3f m/s, Ergun -dp/dz = %.4e Pa/m (inertial term %.1f %%)\n", U,
              want, 100 * inert / want);
  for (DragCoupling c : {DragCoupling::Implicit, DragCoupling::SemiImplicit})
    for (auto [dt, cfl, steps] : {std::tuple{1e-5, 0.5, 60}, std::tuple{1e-4, 0.5, 40}, std::tuple{1e-3, 1.0, 40}}) {
      double dt_used = 0, iters = 0;
      const double g = forchheimer_gradient(U, dt, cfl, steps, c, &dt_used, &iters);
      const double err = test::rel_err(g, want);
      std::printf("[ implicit drag ] Forchheimer bed, %s, fluid step %.2e s (asked %.0e, CFL %.1f): -dp/dz = %.4e "
                  "Pa/m, rel err %.2e (tol 2e-2), %.1f air steps per fluid step\n",
                  c == DragCoupling::Implicit ? "implicit" : "semi-implicit", dt_used, dt, cfl, g, err, iters);
      EXPECT_LT(err, 2e-2);
    }
}
