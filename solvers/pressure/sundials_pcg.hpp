// Conjugate gradients through SUNDIALS' SUNLinSol_PCG with a matrix-free ATimes.
//
// Solves A x = b for a symmetric positive (semi-)definite A given as a callback, optionally with
// a symmetric preconditioner z = M^{-1} r. SUNDIALS stops when the unpreconditioned residual of
// its recurrence satisfies ||r||_2 <= abs_tol.
//
// The N_Vectors are serial NVECTORs whose operations used by PCG (DotProd, LinearSum, Scale,
// Prod, Const) are replaced by OpenMP loops with a fixed reduction blocking, so the iterates are
// bitwise independent of the number of threads (the stock OpenMP NVECTOR reduces per thread).
#pragma once
#include <functional>

namespace cgdem::pressure {

class SundialsPcg {
 public:
  using Apply = std::function<void(const double* in, double* out)>;
  struct Result {
    int iterations = 0;
    double res_norm = 0;  // ||r|| of the PCG recurrence at exit
    bool converged = false;
  };
  // prec may be empty: plain CG.
  SundialsPcg(long n, Apply op, Apply prec);
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
