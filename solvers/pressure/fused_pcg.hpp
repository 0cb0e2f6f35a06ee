// Preconditioned conjugate gradients on the Poisson7 operator with fused vector passes.
//
// The recurrence of SUNDIALS' SUNLinSol_PCG (left preconditioning, stop when the 2-norm of the
// recurrence residual is <= abs_tol):
//   r = b - A x,  z = M^{-1} r,  p = z,  rz = r.z
//   repeat:  q = A p,  alpha = rz / p.q,  x += alpha p,  r -= alpha q,  stop if ||r|| <= tol,
//            z = M^{-1} r,  beta = r.z_new / rz,  rz = r.z_new,  p = z + beta p
// in four passes over memory per iteration besides M^{-1}: (q = A p with p.q), (x, r and
// r.r together), (r.z), (p). SUNDIALS does each operation as its own pass (eight). Sums use
// fixed blocks (row partials for p.q), so the iterates do not depend on the thread count.
#pragma once
#include <functional>
#include <vector>

#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

class FusedPcg {
 public:
  using Apply = std::function<void(const double* in, double* out)>;
  struct Result {
    int iterations = 0;
    double res_norm = 0;  // ||r|| of the recurrence at exit
    bool converged = false;
  };
  // op must outlive the solver; prec may be empty (plain CG).
  FusedPcg(const Poisson7& op, Apply prec) : op_(op), prec_(std::move(prec)) {}
  // x: initial guess on entry (ignored if zero_guess), solution on exit.
  Result solve(const double* b, double* x, double abs_tol, int max_iter, bool zero_guess);

 private:
  const Poisson7& op_;
  Apply prec_;
  std::vector<double> r_, z_, p_, q_, part_;
};

}  // namespace cgdem::pressure
