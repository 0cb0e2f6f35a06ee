// Geometric multigrid V-cycle used as a PCG preconditioner ("pcg-mg").
//
// Levels: the fine grid, then grids coarsened by 2 per axis (n_c = ceil(n/2), h_c = 2h, same
// boundary conditions) while the level has more than kCoarsestCells cells, every axis has
// n >= 4, and periodic axes have even n. The coarse operator is re-discretised from face-averaged
// coefficients: a_c on a coarse face = mean of a over the (up to 2x2) fine faces it covers.
// Transfers: piecewise-constant prolongation P (x_f += x_c(parent)), restriction R = P^T / 8.
// Smoother: red-black Gauss-Seidel, nu sweeps red->black before and black->red after the
// coarse correction, so the V-cycle is a symmetric operator (required by PCG). Coarsest level:
// CHOLMOD with pinned floating components (cholmod_factor.hpp).
//   V(l, b):  x = 0; x <- S^nu(x, b); b_c = R (b - A x); x += P V(l+1, b_c); x <- (S^T)^nu(x, b)
// Precision: Single (default of "pcg-mg", "pcg-mg2") runs the V-cycle on float copies of the
// operators (stencil32.hpp; r is rounded to float on entry, z = s x on exit, the coarsest solve
// in double); Double ("pcg-mg-f64", "pcg-mg2-f64") runs it on the Poisson7 operators. Single
// halves the memory traffic of the smoother; PCG and its residual stay in double.
#pragma once
#include <memory>
#include <vector>

#include "solvers/pressure/cholmod_factor.hpp"
#include "solvers/pressure/preconditioner.hpp"
#include "solvers/pressure/stencil32.hpp"

namespace cgdem::pressure {

class MultigridPreconditioner : public Preconditioner {
 public:
  static constexpr long kCoarsestCells = 4000;
  enum class Precision { Single, Double };
  explicit MultigridPreconditioner(const GridSpec& fine, int nu = 1, Precision prec = Precision::Single);
  ~MultigridPreconditioner() override;
  void setup(const Poisson7& op) override;
  void apply(const double* r, double* z) override;
  int levels() const { return static_cast<int>(grids_.size()); }

 private:
  struct Level {
    std::unique_ptr<Poisson7> own;  // coarse levels own their operator
    const Poisson7* op = nullptr;
    std::vector<double> b, x, r;
    Stencil32 s32;              // Single: the float operator (scaled by scale_)
    std::vector<float> bf, xf;  // Single: right-hand side and iterate
  };
  void vcycle(int l);
  void vcycle32(int l);

  std::vector<GridSpec> grids_;
  std::vector<Level> lv_;
  std::unique_ptr<CholmodFactor> coarse_;
  int nu_;
  Precision precision_;
  double scale_ = 1;  // Single: the float operators are scale_ A
  const double* b0_ = nullptr;  // level 0: the caller's r and z
  double* x0_ = nullptr;
};

}  // namespace cgdem::pressure
