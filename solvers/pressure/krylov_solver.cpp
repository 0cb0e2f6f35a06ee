// Krylov pressure solvers; see krylov_solver.hpp.
#include "solvers/pressure/krylov_solver.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/timers.hpp"

namespace cgdem::pressure {

void check_solve_args(const GridSpec& g, const std::vector<double>& rhs, const std::vector<double>& phi) {
  const long n = g.cells();
  if (static_cast<long>(rhs.size()) != n || static_cast<long>(phi.size()) != n)
    throw Error("pressure: rhs and phi need " + std::to_string(n) + " cells (got " +
                std::to_string(rhs.size()) + " and " + std::to_string(phi.size()) + ")");
}

KrylovSolver::KrylovSolver(const GridSpec& g, const SolverOptions& opt, std::unique_ptr<Preconditioner> prec,
                           Engine engine)
    : opt_(opt),
      op_(g),
      prec_(std::move(prec)),
      pcg_(g.cells(), [this](const double* x, double* y) { op_.apply(x, y); },
           prec_ ? SundialsPcg::Apply([this](const double* r, double* z) {
             prec_->apply(r, z);
             // keeps M symmetric on the mean-free subspace
             op_.project_floating(z, prec_->zero_outside_active());
           })
                 : SundialsPcg::Apply(),
           // PCG's vector operations skip the blocked cells when the preconditioner reads r
           // only on the active segments (sundials_pcg.hpp) or there is none.
           !prec_ || prec_->zero_outside_active() ? &op_.active() : nullptr, g.nx),
      fused_(op_, prec_ ? FusedPcg::Apply([this](const double* r, double* z) {
        prec_->apply(r, z);
        op_.project_floating(z, prec_->zero_outside_active());
      })
                        : FusedPcg::Apply()),
      engine_(engine) {
  if (!(opt.rel_tol > 0) || opt.max_iter < 1)
    throw Error("pressure: rel_tol must be > 0 and max_iter >= 1");
}

void KrylovSolver::set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                                    const std::vector<double>& az) {
  op_.set(ax, ay, az);
  if (prec_) prec_->setup(op_);
  have_coef_ = true;
}

void KrylovSolver::set_rel_tol(double rel_tol) {
  if (!(rel_tol > 0)) throw Error("pressure: rel_tol must be > 0");
  opt_.rel_tol = rel_tol;
}

SolveStats KrylovSolver::solve(const std::vector<double>& rhs, std::vector<double>& phi) {
  if (!have_coef_) throw Error("pressure: solve() called before set_coefficients()");
  check_solve_args(op_.grid(), rhs, phi);
  Stopwatch sw;
  const long n = op_.n();
  b_.resize(n);
  r_.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long c = 0; c < n; ++c) b_[c] = -rhs[c];  // div(a grad phi) = rhs  <=>  A phi = -rhs
  op_.project_floating(b_.data());
  const double bnorm = norm2(b_.data(), n);
  SolveStats st;
  if (bnorm == 0) {
    std::fill(phi.begin(), phi.end(), 0.0);
    st.converged = true;
    st.seconds = sw.seconds();
    return st;
  }
  const bool zero_guess = std::all_of(phi.begin(), phi.end(), [](double v) { return v == 0.0; });
  int iterations = 0;
  bool converged = false;
  if (engine_ == Engine::Fused) {
    const auto res = fused_.solve(b_.data(), phi.data(), opt_.rel_tol * bnorm, opt_.max_iter, zero_guess);
    iterations = res.iterations, converged = res.converged;
  } else {
    const auto res = pcg_.solve(b_.data(), phi.data(), opt_.rel_tol * bnorm, opt_.max_iter, zero_guess);
    iterations = res.iterations, converged = res.converged;
  }
  op_.project_floating(phi.data());
  op_.residual(b_.data(), phi.data(), r_.data());
  st.iterations = iterations;
  st.rel_residual = norm2(r_.data(), n) / bnorm;
  // The recurrence residual may drift from the true one; report the true one and require both.
  st.converged = converged && st.rel_residual <= 10 * opt_.rel_tol;
  st.seconds = sw.seconds();
  return st;
}

}  // namespace cgdem::pressure
