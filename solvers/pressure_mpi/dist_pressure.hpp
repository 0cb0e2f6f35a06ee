// Distributed pressure solve (issue 6, item 3 of docs/scale_out.md): the problem of
// solvers/pressure/pressure_solver.hpp, div(a grad phi) = rhs, on the blocks of GridBlocks.
//
// SUNDIALS' PCG (SUNLinSol_PCG) on its MPI NVECTOR (N_VNew_Parallel: local arrays, dot
// products reduced over the communicator), with the matrix-free operator of dist_poisson.hpp
// (one exchange of the cell layers next to the cuts per product) and one of these
// preconditioners (DistOptions::preconditioner):
//
//   "none"    plain CG (reference);
//   "bj-mg"   block Jacobi: the serial multigrid V-cycle of multigrid.hpp (pcg-mg: float,
//             one sweep per side) on each rank's block; "bj-mg2" two sweeps per side;
//   "bj-fft"  block Jacobi with the diagonally scaled FFT Poisson solve of
//             fft_preconditioner.hpp on each block;
//   "as-mg"   additive Schwarz: the pcg-mg V-cycle on each block grown by kGhost cells on
//             its cut sides (residual and coefficients there from the neighbours), the
//             grown parts of the result added back to their owners; "as-mg2" two sweeps;
//   "pfmg"    hypre's structured multigrid PFMG (one V-cycle, Galerkin coarse operators,
//             symmetric red-black Gauss-Seidel) on the whole distributed grid.
//
// Block Jacobi solves with the diagonal block A_bb of A on each block: a cut face keeps its
// weight on the diagonal and drops the coupling to the other block. That is the block's own
// problem with the cut side Open and half the cut face's coefficient (an Open face adds
// 2 a/h^2 to the diagonal), so the serial preconditioners run on it unchanged. Unlike a
// zero-flux (Wall) cut, A_bb is not singular when the block has no Open side, so the
// preconditioner stays SPD. On one rank "bj-mg" is exactly the serial "pcg-mg" preconditioner.
//
// Singular parts are handled as in the serial KrylovSolver: rhs, the preconditioned residual
// and phi are projected onto the mean-free subspace of every floating component (here
// components spread over several ranks). Dot products become global reductions, so the
// iterates differ from the serial ones at round-off, and also between rank counts.
#pragma once
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "solvers/pressure_mpi/dist_poisson.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::air_mpi {

struct DistOptions {
  // none, bj-mg, bj-mg2, bj-fft, as-mg, as-mg2, pfmg. The default needs no hypre; pfmg is
  // the one whose iterations do not grow with the ranks, as-mg2 the fastest on 2 ranks of
  // Case 1-3 (docs/scale_out.md, item 3 and "Air over ranks"; `cgdem run` chooses).
  std::string preconditioner = "bj-mg";
  double rel_tol = 1e-8;                 // ||r|| <= rel_tol ||b|| (global norms)
  int max_iter = 500;
};

// A preconditioner z ~= A^{-1} r on this rank's cells; linear and symmetric over the ranks.
class DistPreconditioner {
 public:
  virtual ~DistPreconditioner() = default;
  virtual void setup(DistPoisson& op) = 0;                 // collective
  virtual void apply(const double* r, double* z) = 0;     // collective
};

// Throws cgdem::Error for an unknown name (or "pfmg" in a build without hypre).
std::unique_ptr<DistPreconditioner> make_dist_preconditioner(const std::string& name, const DistPoisson& op);

// A pressure::PressureSolver on this rank's block (the FluidSolver of a block takes it).
class DistPressureSolver final : public pressure::PressureSolver {
 public:
  // Throws cgdem::Error (on every rank) for bad options, a grid that disagrees with blocks, or
  // a periodic side.
  DistPressureSolver(MPI_Comm comm, const GridBlocks& blocks, const pressure::GridSpec& global,
                     const DistOptions& opt);
  ~DistPressureSolver() override;
  DistPressureSolver(const DistPressureSolver&) = delete;
  DistPressureSolver& operator=(const DistPressureSolver&) = delete;

  // This block's face coefficients in its local MAC layout (dist_poisson.hpp). Collective.
  void set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                        const std::vector<double>& az) override;
  // rhs and phi on this block's cells; phi is the initial guess on entry (a zero guess when
  // it is zero on every rank). Stats are global (iterations, rel_residual, seconds of this
  // rank). Collective.
  pressure::SolveStats solve(const std::vector<double>& rhs, std::vector<double>& phi) override;
  void set_rel_tol(double rel_tol) override;
  DistPoisson& op() { return op_; }

 private:
  struct Pcg;
  DistOptions opt_;
  DistPoisson op_;
  std::unique_ptr<DistPreconditioner> prec_;
  std::unique_ptr<Pcg> pcg_;
  bool have_coef_ = false;
  std::vector<double> b_, r_;
};

}  // namespace cgdem::air_mpi
