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
// Cycle::W solves each coarse problem above the coarsest with two cycles instead of one (the
// second starts from the first one's x_c, on the same b_c):
//   W(l, b, x): x <- S^nu(x, b); b_c = R (b - A x); x_c = W(l+1, b_c, 0); x_c = W(l+1, b_c, x_c);
//               x += P x_c; x <- (S^T)^nu(x, b)
// Two steps of a symmetric iteration from zero are symmetric again (B_2 = 2B - B A B), so the
// W-cycle is a valid PCG preconditioner too. It visits level l 2^l times (work per level 8^-l
// of the fine level's): 1 + 2/8 + 4/64 + ... = 4/3 of the fine level's work at most, against
// 8/7 for the V-cycle. The extra coarse work pays on the die-filling grid, whose coarse levels
// are poor approximations (piecewise-constant P, face-averaged coefficients across the high
// contrast of air and packed bed): docs/pressure.md.
// Precision: Single (default of "pcg-mg", "pcg-mg2", "pcg-mgw3") runs the cycle on float copies of
// the operators (stencil32.hpp; r is rounded to float on entry, z = s x on exit, the coarsest solve
// in double); Double ("pcg-mg-f64", "pcg-mg2-f64", "pcg-mgw3-f64") runs it on the Poisson7 operators. Single
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
  enum class Cycle { V, W };
  // omega: relaxation factor of the red-black smoother (1: Gauss-Seidel; the same in every
  // half-sweep, so the cycle stays symmetric).
  // skip_blocked (Single): the cycle visits only the cells it needs (below; false: every cell,
  // the same z on the cells with D > 0, for the tests).
  explicit MultigridPreconditioner(const GridSpec& fine, int nu = 1, Precision prec = Precision::Single,
                                   Cycle cycle = Cycle::V, double omega = 1.0, bool skip_blocked = true);
  ~MultigridPreconditioner() override;
  void setup(const Poisson7& op) override;
  void apply(const double* r, double* z) override;
  // The single-precision cycle on more than one level skips those cells (stencil32.hpp).
  bool zero_outside_active() const override {
    return skip_blocked_ && precision_ == Precision::Single && levels() > 1;
  }
  int levels() const { return static_cast<int>(grids_.size()); }

 private:
  struct Level {
    std::unique_ptr<Poisson7> own;  // coarse levels own their operator
    const Poisson7* op = nullptr;
    std::vector<double> b, x, r;
    Stencil32 s32;              // Single: the float operator (scaled by scale_)
    ActiveRows act;             // Single, coarse levels: the cells the cycle visits
    std::vector<float> bf, xf;  // Single: right-hand side and iterate
  };
  // One cycle on level l (V or W, cycle_); from_zero: x = 0 on entry (else the current x).
  void vcycle(int l, bool from_zero);
  void vcycle32(int l, bool from_zero);

  std::vector<GridSpec> grids_;
  std::vector<Level> lv_;
  std::unique_ptr<CholmodFactor> coarse_;
  int nu_;
  Precision precision_;
  Cycle cycle_;
  double omega_;
  bool skip_blocked_;
  ActiveRows fine_seen_;  // the finest level's segments that lv_[l].act were derived from
  double scale_ = 1;  // Single: the float operators are scale_ A
  const double* b0_ = nullptr;  // level 0: the caller's r and z
  double* x0_ = nullptr;
};

}  // namespace cgdem::pressure
