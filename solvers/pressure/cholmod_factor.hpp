// Sparse Cholesky of the 7-point operator A = -div(a grad .) (poisson7.hpp) with CHOLMOD.
//
// A is assembled as a symmetric CSC matrix (lower triangle, stype = -1). On every floating
// component (no Open face: A singular there with a constant null vector) one cell is pinned:
//   A' = A + d e_p e_p^T   (d = D_p, or 1 for an isolated cell).
// For a right-hand side b that is mean-free on the component, summing the rows of A' x = b
// gives d x_p = 0, hence A x = b exactly; the caller then removes the component mean.
// Used as the "cholmod" direct method and as the coarsest-level solve of the multigrid.
#pragma once
#include <memory>

#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

class CholmodFactor {
 public:
  explicit CholmodFactor(const Poisson7& op);  // assemble, analyse, factorise (throws on failure)
  // The factor of another operator on the same grid. When the matrix has the pattern of the
  // one last analysed (the same nonzeros, as when only the coefficients' values changed),
  // the analysis (fill-reducing order, symbolic factor) is kept and only the numbers are
  // factorised again: the same factor, to the bit, as a new CholmodFactor(op) gives, since
  // the analysis depends on the pattern alone. Otherwise it analyses anew. Returns whether
  // the analysis was kept.
  bool refactor(const Poisson7& op);
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;
  // x = A'^{-1} b (arrays of op.n() values; b and x may alias).
  void solve(const double* b, double* x);
  double factor_nonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cgdem::pressure
