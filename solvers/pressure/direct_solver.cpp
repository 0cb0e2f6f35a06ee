// Direct CHOLMOD pressure solver; see direct_solver.hpp.
#include "solvers/pressure/direct_solver.hpp"

#include "core/error.hpp"
#include "core/timers.hpp"
#include "solvers/pressure/krylov_solver.hpp"

namespace cgdem::pressure {

void DirectSolver::set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                                    const std::vector<double>& az) {
  op_.set(ax, ay, az);
  factor_.reset();
  factor_ = std::make_unique<CholmodFactor>(op_);
}

void DirectSolver::set_rel_tol(double rel_tol) {
  if (!(rel_tol > 0)) throw Error("pressure: rel_tol must be > 0");
  opt_.rel_tol = rel_tol;
}

SolveStats DirectSolver::solve(const std::vector<double>& rhs, std::vector<double>& phi) {
  if (!factor_) throw Error("pressure: solve() called before set_coefficients()");
  check_solve_args(op_.grid(), rhs, phi);
  Stopwatch sw;
  const long n = op_.n();
  b_.resize(n);
  r_.resize(n);
  for (long c = 0; c < n; ++c) b_[c] = -rhs[c];  // A phi = -rhs
  op_.project_floating(b_.data());
  factor_->solve(b_.data(), phi.data());
  op_.project_floating(phi.data());
  op_.residual(b_.data(), phi.data(), r_.data());
  SolveStats st;
  const double bnorm = norm2(b_.data(), n);
  st.iterations = 1;
  st.rel_residual = bnorm > 0 ? norm2(r_.data(), n) / bnorm : 0.0;
  st.converged = st.rel_residual <= opt_.rel_tol;
  st.seconds = sw.seconds();
  return st;
}

}  // namespace cgdem::pressure
