// Fast constant-coefficient Poisson solve used as a PCG preconditioner ("pcg-fft").
//
// L is the 7-point operator -lap with unit coefficient and the domain boundary conditions; it is
// diagonalised per axis by real-to-real transforms of the cell-centred grid:
//   Wall-Wall  DCT-II / DCT-III (REDFT10/01)  theta_m = pi m / n
//   Open-Open  DST-II / DST-III (RODFT10/01)  theta_m = pi (m+1) / n
//   Wall-Open  DCT-IV (REDFT11)               theta_m = pi (m+1/2) / n
//   Open-Wall  DST-IV (RODFT11)               theta_m = pi (m+1/2) / n
//   Periodic   real DFT, halfcomplex (R2HC/HC2R) theta_m = 2 pi min(m, n-m) / n
// with eigenvalues lambda = sum_axis (2 - 2 cos theta)/h^2 (the zero mode of a singular L is
// dropped: pseudo-inverse). Two variants:
//   Scaling::None      M^{-1} = L^{-1}   (freezing a to any constant a0 gives the same PCG
//                                         iterates: PCG is invariant to scaling M)
//   Scaling::Diagonal  M^{-1} = D^{-1/2} L^{-1} D^{-1/2} d_L,  D = diag(A), d_L = diag(L)
//                      (symmetric; a cell with D = 0, i.e. all faces blocked, gets z = 0)
// Plans are made once per grid with FFTW_MEASURE, threaded through fftw3_omp with the OpenMP
// thread count current at construction (grids below 2^17 cells: FFTW_ESTIMATE, one thread). (MEASURE may pick a different algorithm per run, so
// iterates can differ from run to run at round-off level.)
#pragma once
#include <memory>
#include <vector>

#include "solvers/pressure/preconditioner.hpp"

namespace cgdem::pressure {

class FftPreconditioner : public Preconditioner {
 public:
  enum class Scaling { None, Diagonal };
  FftPreconditioner(const GridSpec& g, Scaling s);
  ~FftPreconditioner() override;
  void setup(const Poisson7& op) override;
  void apply(const double* r, double* z) override;

 private:
  struct Plans;
  GridSpec g_;
  Scaling scaling_;
  std::unique_ptr<Plans> plans_;
  std::vector<double> inv_lambda_;  // 1/(lambda * normalisation), 0 for the null mode
  std::vector<double> dscale_;      // D^{-1/2} sqrt(d_L) (Diagonal) or 1 / 0 mask (None)
};

}  // namespace cgdem::pressure
