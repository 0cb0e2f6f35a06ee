// Conjugate gradients through SUNDIALS' SUNLinSol_PCG with a matrix-free ATimes.
//
// Solves A x = b for a symmetric positive (semi-)definite A given as a callback, optionally with
// a symmetric preconditioner z = M^{-1} r. SUNDIALS stops when the unpreconditioned residual of
// its recurrence satisfies ||r||_2 <= abs_tol.
//
// The N_Vectors are serial NVECTORs whose operations used by PCG (DotProd, LinearSum, Scale,
// Prod, Const) are replaced by OpenMP loops with a fixed reduction blocking, so the iterates are
// bitwise independent of the number of threads (the stock OpenMP NVECTOR reduces per thread).
//
// Given the grid's active cells (active_rows.hpp), the operations PCG repeats every iteration
// (DotProd, LinearSum, Scale) visit only their segments. That is the same iteration when
// nothing outside them can reach the segments: the operator writes A p = 0 there and reads
// those cells through weights of 0, and the preconditioner must read r only on the segments
// (then whatever PCG leaves in r, z, p, x outside them is never used; the caller sets phi
// there afterwards). The dot products skip only products with a 0 (r = 0, A p = 0 there), in
// the same blocks and order: the same sums. The work vectors start at 0, so every value
// outside the segments stays finite.
#pragma once
#include <functional>

#include "solvers/pressure/active_rows.hpp"

namespace cgdem::pressure {

class SundialsPcg {
 public:
  using Apply = std::function<void(const double* in, double* out)>;
  struct Result {
    int iterations = 0;
    double res_norm = 0;  // ||r|| of the PCG recurrence at exit
    bool converged = false;
  };
  // prec may be empty: plain CG. active (with nx cells per row; it must outlive the solver and
  // may change between solves): the cells the per-iteration operations visit (above); nullptr:
  // all n.
  SundialsPcg(long n, Apply op, Apply prec, const ActiveRows* active = nullptr, int nx = 0);
  ~SundialsPcg();
  SundialsPcg(const SundialsPcg&) = delete;
  SundialsPcg& operator=(const SundialsPcg&) = delete;

  // x: initial guess on entry (ignored if zero_guess), solution on exit.
  Result solve(const double* b, double* x, double abs_tol, int max_iter, bool zero_guess);

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace cgdem::pressure
