// The 7-point pressure operator of solvers/pressure/poisson7.hpp on the blocks of GridBlocks
// (issue 6, item 3 of docs/scale_out.md): each rank holds the cells of its block.
//
//     (A phi)_c = sum_f w_f (phi_c - phi_nb(f)) + sum_{open f} 2 w_f phi_c,   w_f = a_f / h_f^2,
//
// the same face coefficients and Wall / Open sides as the serial problem (pressure_solver.hpp).
// Periodic sides are refused. Local arrays: cells i + nx (j + ny k) of the block, faces in the
// MAC layout of the block ((nx+1) ny nz for x faces, ...), local indices.
//
// Coefficients on a cut: the face between two blocks belongs to the upper block (its face 0,
// as in grid_blocks.hpp). set() takes the upper block's value for it and overwrites the lower
// block's copy (its face n), so both sides use the same weight even if the caller's ghost
// copy were stale.
//
// apply() needs the neighbours' cells next to the cuts: one exchange of one cell layer per
// cut side, overlapped with the interior part of the product.
//
// Floating components (connected by faces with w > 0, no Open face of positive weight) are
// labelled across the ranks: each rank labels its block, the labels of the cells next to each
// cut are exchanged, and the (small) graph of the components that touch a cut is gathered on
// every rank and joined the same way everywhere. project_floating() then subtracts, on every
// floating component, its mean: sums over a component spread over several ranks are reduced
// with one MPI_Allreduce (only when such a component exists). As in the serial solver, a cell
// with all faces blocked gets 0.
//
// Every method except the accessors is collective over the communicator.
#pragma once
#include <mpi.h>

#include <vector>

#include "parallel/grid_blocks.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::air_mpi {

class DistPoisson {
 public:
  // Throws cgdem::Error for a grid that disagrees with blocks, bad spacings, or a periodic side.
  DistPoisson(MPI_Comm comm, const GridBlocks& blocks, const pressure::GridSpec& global);

  // Face coefficients a >= 0 of this block (local MAC layout; see above). Throws on size/sign.
  void set(const std::vector<double>& ax, const std::vector<double>& ay, const std::vector<double>& az);
  // y = A x on this block's cells.
  void apply(const double* x, double* y);
  // Subtract its mean on every floating component (global components).
  void project_floating(double* v);

  MPI_Comm comm() const { return comm_; }
  const GridBlocks& blocks() const { return blocks_; }
  const pressure::GridSpec& global() const { return global_; }
  // The block as a grid of its own: local cells, the global spacings, the global sides on the
  // physical boundary and `cut` on the cut sides.
  pressure::GridSpec local_spec(pressure::Boundary cut) const;
  long n() const { return n_; }
  long global_n() const { return global_.cells(); }
  // Face coefficients as used (the cut faces synchronised, see above), local MAC layout.
  const std::vector<double>& ax() const { return a_[0]; }
  const std::vector<double>& ay() const { return a_[1]; }
  const std::vector<double>& az() const { return a_[2]; }
  // Weights a/h^2 of the faces that couple two cells (interior and cut faces; physical
  // boundary faces hold 0), and the diagonal including the Open terms.
  const std::vector<double>& w(int axis) const { return w_[axis]; }
  const std::vector<double>& diag() const { return diag_; }
  bool singular() const { return singular_; }
  int floating_components() const { return n_floating_; }  // over all ranks

 private:
  // The steps of set() after the checks: the cut faces' coefficients from the upper block
  // (a_), then the weights, the diagonal and the Open terms (w_, diag_, open_), then the
  // floating components (comp_ and the rest below).
  void sync_cut_faces();
  void assemble_weights();
  void label_components();
  void exchange_layers(const double* x);
  void exchange_finish();

  MPI_Comm comm_;
  GridBlocks blocks_;
  pressure::GridSpec global_;
  int nx_, ny_, nz_;
  long n_;
  std::vector<double> a_[3], w_[3], diag_, open_;
  // Face halo of one cell layer per side: what this rank sends and what it receives.
  std::vector<double> hs_[6], hr_[6];
  MPI_Request req_[12];
  int nreq_ = 0;
  // Floating components: per cell, -1 (grounded), a local component (0..), or a component
  // spread over ranks (encoded as -2 - q).
  std::vector<int> comp_;
  std::vector<double> local_count_, cross_count_;
  std::vector<double> local_sum_, cross_sum_;
  std::vector<long> isolated_, floating_cells_;  // one-cell components; cells with comp_ != -1
  std::vector<double> zero_;  // weights of the missing neighbours in apply()
  bool singular_ = false;
  int n_floating_ = 0;
};

}  // namespace cgdem::air_mpi
