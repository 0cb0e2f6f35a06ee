// The fused PCG (fused_pcg.hpp) runs the recurrence of SUNDIALS' SUNLinSol_PCG: on the same
// problem, preconditioner and initial guess both engines must take the same number of iterations
// and agree to rounding (reference: the SUNDIALS engine), from a zero and a non-zero guess.
// Preconditioned runs only (10-30 iterations): unpreconditioned CG takes ~170 iterations here
// and amplifies the different rounding of p.Ap (row partials vs blocks) beyond 1e-12 (it uses
// the SUNDIALS engine in the "cg" method anyway).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mms.hpp"
#include "solvers/pressure/fft_preconditioner.hpp"
#include "solvers/pressure/krylov_solver.hpp"
#include "solvers/pressure/multigrid.hpp"

using namespace cgdem::pressure;
using B = Boundary;
using E = KrylovSolver::Engine;

namespace {
std::unique_ptr<Preconditioner> make_prec(const std::string& name, const GridSpec& g) {
  if (name == "mg") return std::make_unique<MultigridPreconditioner>(g, 2);
  if (name == "fft") return std::make_unique<FftPreconditioner>(g, FftPreconditioner::Scaling::Diagonal);
  return nullptr;
}

void compare(const char* prec, std::array<B, 6> bc, bool warm) {
  const test::Problem p = test::make_problem(24, 20, 16, bc);
  SolverOptions opt;
  opt.rel_tol = 1e-10;
  opt.max_iter = 2000;
  KrylovSolver fused(p.g, opt, make_prec(prec, p.g), E::Fused), sun(p.g, opt, make_prec(prec, p.g), E::Sundials);
  fused.set_coefficients(p.ax, p.ay, p.az);
  sun.set_coefficients(p.ax, p.ay, p.az);
  std::vector<double> a(p.g.cells(), 0.0), b(p.g.cells(), 0.0);
  if (warm)
    for (long c = 0; c < p.g.cells(); ++c) a[c] = b[c] = std::sin(0.1 * c);
  const auto sf = fused.solve(p.rhs, a), ss = sun.solve(p.rhs, b);
  double d = 0, m = 0;
  for (size_t c = 0; c < a.size(); ++c) d = std::max(d, std::abs(a[c] - b[c])), m = std::max(m, std::abs(b[c]));
  std::printf("[ fused ] %-3s %s guess: iterations fused %d / sundials %d, residual %.2e / %.2e, "
              "max diff %.2e (tol 1e-12)\n", prec, warm ? "warm" : "zero", sf.iterations, ss.iterations,
              sf.rel_residual, ss.rel_residual, d / m);
  EXPECT_TRUE(sf.converged);
  EXPECT_EQ(sf.iterations, ss.iterations);
  EXPECT_LT(d / m, 1e-12);
}
}  // namespace

TEST(PressureFusedPcg, SameIteratesAsSundials) {
  const std::array<B, 6> mixed{B::Wall, B::Open, B::Periodic, B::Periodic, B::Wall, B::Wall};
  const std::array<B, 6> closed{B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Wall};  // singular
  for (bool warm : {false, true}) {
    compare("mg", mixed, warm);
    compare("fft", mixed, warm);
    compare("mg", closed, warm);
  }
}
