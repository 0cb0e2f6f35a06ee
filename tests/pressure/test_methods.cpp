// Cross-method agreement, blocked faces (a = 0), singular problems, thread independence and bad
// input for the pressure solvers. Tolerances are stated at each check and the errors printed.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "mms.hpp"
#include "solvers/pressure/multigrid.hpp"

using namespace cgdem::pressure;
using B = Boundary;

namespace {
std::vector<double> solve_with(const test::Problem& p, const std::string& method, SolveStats* out = nullptr) {
  SolverOptions opt;
  opt.method = method;
  opt.rel_tol = 1e-10;
  opt.max_iter = 5000;
  auto s = make_pressure_solver(p.g, opt);
  s->set_coefficients(p.ax, p.ay, p.az);
  std::vector<double> phi(p.g.cells(), 0.0);
  const auto st = s->solve(p.rhs, phi);
  EXPECT_TRUE(st.converged) << method;
  if (out) *out = st;
  return phi;
}

double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, m = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    m = std::max(m, std::abs(b[i]));
  }
  return d / m;
}

// All methods against CHOLMOD: rel_tol 1e-10 times a condition number <~ 1e3 -> tol 1e-7.
void agreement(const char* name, std::array<B, 6> bc, test::Problem p) {
  (void)bc;
  const auto ref = solve_with(p, "cholmod");
  for (const std::string& method : pressure_method_names()) {  // every registered method
    if (method == "cholmod") continue;
    const char* m = method.c_str();
    SolveStats st;
    const auto phi = solve_with(p, m, &st);
    const double d = max_diff(phi, ref);
    std::printf("[ agree %s ] %-13s iterations %4d, rel residual %.2e, max |phi - phi_cholmod|/max|phi| = %.2e (tol 1e-7)\n",
                name, m, st.iterations, st.rel_residual, d);
    EXPECT_LE(d, 1e-7) << m;
  }
}
}  // namespace

TEST(PressureMethods, AgreeAllBoundaryTypes) {
  const std::array<std::array<B, 6>, 4> bcs = {{{B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Wall},
                                                {B::Open, B::Open, B::Open, B::Open, B::Open, B::Open},
                                                {B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic, B::Periodic},
                                                {B::Periodic, B::Periodic, B::Open, B::Wall, B::Wall, B::Open}}};
  const char* names[4] = {"wall", "open", "periodic", "mixed"};
  for (int q = 0; q < 4; ++q) agreement(names[q], bcs[q], test::make_problem(24, 20, 16, bcs[q]));
}

// A blocked plane of x faces at x = 1/2 splits an Open-Open x channel (Wall in y, z) into two
// halves with Neumann at the plane. rhs = f on the left, 2 f on the right with f = -pi^2 sin(pi x)
// (a = 1): exact phi = sin(pi x) left, 2 sin(pi x) right (jump at the plane).
TEST(PressureMethods, BlockedFacesClosedForm) {
  double err[3];
  for (int s = 0; s < 3; ++s) {
    const int nx = 16 << s, ny = 3, nz = 3;
    test::Problem p;
    p.g = GridSpec{nx, ny, nz, 1.0 / nx, 1.0 / ny, 1.0 / nz, {B::Open, B::Open, B::Wall, B::Wall, B::Wall, B::Wall}};
    p.ax.assign(long(nx + 1) * ny * nz, 1.0);
    p.ay.assign(long(nx) * (ny + 1) * nz, 1.0);
    p.az.assign(long(nx) * ny * (nz + 1), 1.0);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) p.ax[nx / 2 + long(nx + 1) * (j + long(ny) * k)] = 0.0;
    p.rhs.resize(p.g.cells());
    p.exact.resize(p.g.cells());
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const double x = (i + 0.5) / nx, amp = i < nx / 2 ? 1.0 : 2.0;
          p.rhs[i + long(nx) * (j + long(ny) * k)] = -amp * M_PI * M_PI * std::sin(M_PI * x);
          p.exact[i + long(nx) * (j + long(ny) * k)] = amp * std::sin(M_PI * x);
        }
    const auto ref = solve_with(p, "cholmod");
    err[s] = test::max_error(ref, p.exact, false);
    for (const char* m : {"cg", "pcg-fft", "pcg-mg", "pcg-mg-f64"}) {
      SolveStats st;
      const double d = max_diff(solve_with(p, m, &st), ref);
      std::printf("[ blocked ] nx %3d %-8s iterations %3d, diff to cholmod %.2e (tol 1e-7)\n", nx, m, st.iterations, d);
      EXPECT_LE(d, 1e-7);
    }
    std::printf("[ blocked ] nx %3d max error vs exact %.3e\n", nx, err[s]);
  }
  const double order = std::log2(err[1] / err[2]);
  std::printf("[ blocked ] observed order %.2f (tol >= 1.8)\n", order);
  EXPECT_GE(order, 1.8);
}

// Solid cells (every face a = 0) get phi = 0; an air pocket enclosed by a = 0 faces is floating
// and gets mean-free phi, whatever rhs it holds; everything else matches CHOLMOD.
TEST(PressureMethods, SolidCellsAndEnclosedPocket) {
  auto p = test::make_problem(20, 16, 12, {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open});
  const auto& g = p.g;
  auto in_box = [](int i, int j, int k, int i0, int i1, int j0, int j1, int k0, int k1) {
    return i >= i0 && i < i1 && j >= j0 && j < j1 && k >= k0 && k < k1;
  };
  // solid shell: cells in [4,12)x[4,12)x[2,8) except the pocket [6,10)x[6,10)x[4,6)
  auto solid = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= g.nx || j >= g.ny || k >= g.nz) return false;
    return in_box(i, j, k, 4, 12, 4, 12, 2, 8) && !in_box(i, j, k, 6, 10, 6, 10, 4, 6);
  };
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i <= g.nx; ++i)
        if (solid(i - 1, j, k) || solid(i, j, k)) p.ax[i + long(g.nx + 1) * (j + long(g.ny) * k)] = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j <= g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (solid(i, j - 1, k) || solid(i, j, k)) p.ay[i + long(g.nx) * (j + long(g.ny + 1) * k)] = 0;
  for (int k = 0; k <= g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (solid(i, j, k - 1) || solid(i, j, k)) p.az[i + long(g.nx) * (j + long(g.ny) * k)] = 0;
  const auto ref = solve_with(p, "cholmod");
  for (const std::string& method : pressure_method_names()) {  // every registered method
    if (method == "cholmod") continue;
    const char* m = method.c_str();
    SolveStats st;
    const auto phi = solve_with(p, m, &st);
    double solid_max = 0, pocket_sum = 0;
    int pocket_n = 0;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          const double v = phi[i + long(g.nx) * (j + long(g.ny) * k)];
          if (solid(i, j, k)) solid_max = std::max(solid_max, std::abs(v));
          if (in_box(i, j, k, 6, 10, 6, 10, 4, 6)) { pocket_sum += v; ++pocket_n; }
        }
    const double d = max_diff(phi, ref);
    std::printf("[ solids ] %-8s iterations %3d, max|phi| in solid %.1e (tol 0), pocket mean %.1e (tol 1e-12), "
                "diff to cholmod %.2e (tol 1e-7)\n", m, st.iterations, solid_max, pocket_sum / pocket_n, d);
    EXPECT_EQ(solid_max, 0.0);
    EXPECT_LE(std::abs(pocket_sum / pocket_n), 1e-12);
    EXPECT_LE(d, 1e-7);
  }
}

// All-Wall: a constant added to rhs is removed; phi is mean-free and equals the solution for the
// mean-free rhs.
TEST(PressureMethods, SingularGivesMeanFree) {
  auto p = test::make_problem(16, 12, 10, {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Wall});
  const auto phi0 = solve_with(p, "pcg-mg");
  for (auto& v : p.rhs) v += 3.0;
  for (const char* m : {"cg", "pcg-fft", "pcg-mg", "pcg-mg-f64", "cholmod"}) {
    const auto phi = solve_with(p, m);
    const double d = max_diff(phi, phi0);
    std::printf("[ singular ] %-8s mean(phi) %.1e (tol 1e-12), diff to mean-free-rhs solution %.2e (tol 1e-7)\n", m,
                test::mean(phi), d);
    EXPECT_LE(std::abs(test::mean(phi)), 1e-12);
    EXPECT_LE(d, 1e-7);
  }
}

TEST(PressureMethods, ThreadCountIndependent) {
  const auto p = test::make_problem(24, 20, 16, {B::Wall, B::Wall, B::Periodic, B::Periodic, B::Wall, B::Open});
  const int saved = omp_get_max_threads();
  for (const char* m : {"cg", "pcg-fft", "pcg-mg", "pcg-mg-f64"}) {
    omp_set_num_threads(1);
    const auto a = solve_with(p, m);
    omp_set_num_threads(2);
    const auto b = solve_with(p, m);
    const double d = max_diff(a, b);
    std::printf("[ threads ] %-8s 1 vs 2 threads max rel diff %.1e (tol 0: bitwise)\n", m, d);
    EXPECT_EQ(d, 0.0);
  }
  omp_set_num_threads(saved);
}

// The W-cycle on a hierarchy of four levels (the smaller grids above have two, where W = V), with
// a packed-bed-like box of 50x lower coefficient and a solid slab (a = 0): pcg-mgw3 and its double
// twin agree with pcg-mg2, need fewer iterations than it, and do not depend on the thread count.
TEST(PressureMethods, WcycleDeepHierarchy) {
  auto p = test::make_problem(96, 64, 48, {B::Wall, B::Wall, B::Periodic, B::Periodic, B::Wall, B::Open});
  const auto& g = p.g;
  ASSERT_GE(MultigridPreconditioner(g).levels(), 4);
  auto bed = [](int i, int j, int k) { return i >= 20 && i < 60 && j >= 10 && j < 50 && k < 24; };
  auto solid = [](int i, int, int k) { return i >= 60 && i < 62 && k < 30; };
  auto scale = [&](int i0, int j0, int k0, int i1, int j1, int k1) {
    if (solid(i0, j0, k0) || solid(i1, j1, k1)) return 0.0;
    return bed(i0, j0, k0) || bed(i1, j1, k1) ? 0.02 : 1.0;
  };
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i <= g.nx; ++i) p.ax[i + long(g.nx + 1) * (j + long(g.ny) * k)] *= scale(i - 1, j, k, i, j, k);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j <= g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) p.ay[i + long(g.nx) * (j + long(g.ny + 1) * k)] *= scale(i, j - 1, k, i, j, k);
  for (int k = 0; k <= g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) p.az[i + long(g.nx) * (j + long(g.ny) * k)] *= scale(i, j, k - 1, i, j, k);
  SolveStats sv;
  const auto ref = solve_with(p, "pcg-mg2", &sv);
  const int saved = omp_get_max_threads();
  for (const char* m : {"pcg-mgw3", "pcg-mgw3-f64"}) {
    SolveStats sw;
    omp_set_num_threads(1);
    const auto a = solve_with(p, m, &sw);
    omp_set_num_threads(2);
    const auto b = solve_with(p, m);
    const double d = max_diff(a, ref), dt = max_diff(a, b);
    std::printf("[ w-cycle ] %-12s iterations %d (pcg-mg2: %d), diff to pcg-mg2 %.2e (tol 1e-7), "
                "1 vs 2 threads %.1e (tol 0: bitwise)\n", m, sw.iterations, sv.iterations, d, dt);
    EXPECT_LE(d, 1e-7);
    EXPECT_LT(sw.iterations, sv.iterations);
    EXPECT_EQ(dt, 0.0);
  }
  omp_set_num_threads(saved);
}

TEST(PressureMethods, BadInputThrows) {
  GridSpec g{8, 6, 4, 0.1, 0.1, 0.1, {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open}};
  SolverOptions opt;
  opt.method = "gauss-jordan";
  try {
    make_pressure_solver(g, opt);
    ADD_FAILURE() << "no error for an unknown method";
  } catch (const cgdem::Error& e) {  // the message lists every registered method
    for (const auto& m : pressure_methods()) EXPECT_NE(std::string(e.what()).find(m.name), std::string::npos) << e.what();
    std::printf("[ methods ] %s\n", e.what());
  }
  opt.method = "pcg-mg";
  GridSpec bad = g;
  bad.bc[0] = B::Periodic;  // only one side periodic
  EXPECT_THROW(make_pressure_solver(bad, opt), cgdem::Error);
  bad = g;
  bad.nx = 0;
  EXPECT_THROW(make_pressure_solver(bad, opt), cgdem::Error);
  for (const std::string& m : pressure_method_names()) {
    opt.method = m;
    auto s = make_pressure_solver(g, opt);
    std::vector<double> ax(9 * 6 * 4, 1.0), ay(8 * 7 * 4, 1.0), az(8 * 6 * 5, 1.0), rhs(g.cells(), 1.0), phi(g.cells());
    EXPECT_THROW(s->solve(rhs, phi), cgdem::Error) << "solve before set_coefficients";
    std::vector<double> short_ax(ax.size() - 1, 1.0);
    EXPECT_THROW(s->set_coefficients(short_ax, ay, az), cgdem::Error);
    auto neg = ay;
    neg[3] = -1.0;
    EXPECT_THROW(s->set_coefficients(ax, neg, az), cgdem::Error);
    for (const double v : {std::nan(""), HUGE_VAL}) {  // not finite
      auto nonfinite = az;
      nonfinite[az.size() - 1] = v;
      EXPECT_THROW(s->set_coefficients(ax, ay, nonfinite), cgdem::Error);
    }
    s->set_coefficients(ax, ay, az);
    std::vector<double> short_rhs(rhs.size() - 1);
    EXPECT_THROW(s->solve(short_rhs, phi), cgdem::Error);
    std::vector<double> short_phi(phi.size() + 1);
    EXPECT_THROW(s->solve(rhs, short_phi), cgdem::Error);
  }
}
