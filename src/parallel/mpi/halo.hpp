// Halo exchange of the air fields between the blocks of GridBlocks (issue 6, item 2 of
// docs/scale_out.md).
//
// exchange(f, stagger) fills the kGhost ghost layers of f on every cut side with the values
// the neighbouring blocks own. It runs three sweeps, x, then y, then z; each sweep sends one
// message to each of the (up to) two neighbours along its axis and covers the whole padded
// extent of the other two axes, so a later sweep carries the ghosts of the earlier ones
// along: edges and corners arrive with 6 messages instead of 26.
//
// Layers along the sweep axis a, for a block of n cells (s = 1 when f is the face field
// normal to a, else 0; the field then has n + s entries along a):
//     from the lower block:  ghosts [-kGhost, 0)          <- its [n_low - kGhost, n_low)
//     from the upper block:  ghosts [n, n + kGhost + s)   <- its [0, kGhost + s)
// For a face field, index n is the face on the cut, owned by the upper block (its face 0).
//
// Physical sides are not touched: the boundary fill functions of fluid/boundary.hpp own them.
// Use them FIRST, with local_boundary() (cut sides marked Open, whose fills write ghosts only,
// never a face the block owns), then exchange(): the exchange overwrites every cut ghost, and
// since each sweep copies the neighbours' physical ghosts too, the edges where a cut meets a
// physical side get the same values as a serial fill (fill_scalar / fill_velocity below).
//
// reverse_add(f, stagger) is the transpose, for deposits (void fraction, drag coefficients)
// that reach into ghost layers: sweeps z, then y, then x send the cut-side ghost layers to the
// blocks that own those entries, which add them (first the contribution of the lower block,
// then that of the upper block: a fixed order, so the sums are reproducible for a given
// decomposition); the sent ghosts are then zeroed. Deposits into physical-side ghosts are
// routed to the block that holds that ghost, as in a serial deposit. A forward exchange
// afterwards makes the ghosts consistent again.
//
// Every rank of the communicator must call these together (they are collective over the
// neighbours). The communicator's size must equal blocks.ranks().
#pragma once
#include <mpi.h>

#include <vector>

#include "parallel/grid_blocks.hpp"
#include "fluid/boundary.hpp"
#include "fluid/field_sync.hpp"

namespace cgdem::air_mpi {

// Cell-centred fields have no stagger axis (the value of fluid/field_sync.hpp).
inline constexpr int kCellCentred = fluid::kCells;

class Halo {
 public:
  // Throws cgdem::Error when the communicator's size or rank disagrees with blocks.
  Halo(MPI_Comm comm, const GridBlocks& blocks);

  // stagger: kCellCentred, or the axis d of a face field of component d (extent n + e_d).
  void exchange(fluid::Field& f, int stagger);
  void reverse_add(fluid::Field& f, int stagger);

  const GridBlocks& blocks() const { return blocks_; }
  MPI_Comm comm() const { return comm_; }

 private:
  void check_field(const fluid::Field& f, int stagger) const;
  void sweep(fluid::Field& f, int stagger, int axis, bool reverse);

  MPI_Comm comm_;
  GridBlocks blocks_;
  std::vector<double> send_[2], recv_[2];
};

// The global boundary conditions with every cut side replaced by Open (see above).
fluid::FluidBoundary local_boundary(const GridBlocks& blocks, const fluid::FluidBoundary& global);

// Ghost layers of a block's fields, equal to those of a serial fill of the global grid:
// the fills of boundary.hpp on the local grid with local_boundary(), then the exchange.
// Periodic sides are refused (cgdem::Error): the exchange does not wrap.
void fill_scalar(Halo& halo, const fluid::MacGrid& local, const fluid::FluidBoundary& global_bc, fluid::Field& s,
                 fluid::ScalarKind kind);
void fill_velocity(Halo& halo, const fluid::MacGrid& local, const fluid::FluidBoundary& global_bc, fluid::Field& u,
                   fluid::Field& v, fluid::Field& w);

}  // namespace cgdem::air_mpi
