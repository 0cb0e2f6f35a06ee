// An air field of the blocks assembled into the field of the whole grid on one rank, and
// handed out again (issue 6, item 4 of docs/scale_out.md: output that reads as a serial
// run's, checkpoints that restart on another rank count).
//
// Each rank contributes the entries it owns: its cells; for the face field of component d,
// its faces 0 .. n_d - 1 along d, and the face n_d too when the block ends on the domain's
// upper side (on a cut, that face is the upper block's face 0). The union is every interior
// entry of the global field once. Ghost layers are neither sent nor set: after
// scatter_field(), fill them with the boundary fills and the halo exchange (halo.hpp).
#pragma once
#include <mpi.h>

#include "parallel/grid_blocks.hpp"
#include "fluid/mac_grid.hpp"

namespace cgdem::air_mpi {

// Collective over comm (size blocks.ranks()). `local` has this block's extent (cells, or
// cells + e_d for stagger d; halo.hpp's kCellCentred = -1 for cells). `root` receives the
// global field (interior entries; ghosts 0), the others an empty Field. One MPI_Gatherv.
// Throws cgdem::Error for a field of the wrong extent.
fluid::Field gather_field(MPI_Comm comm, const GridBlocks& blocks, const fluid::Field& local, int stagger,
                          int root = 0);

// Collective: the entries this block owns, from `global` (significant on root only), into
// `local` (resized to the block's extent; ghosts and the cut faces it does not own are 0).
// One MPI_Scatterv.
void scatter_field(MPI_Comm comm, const GridBlocks& blocks, const fluid::Field& global, fluid::Field& local,
                   int stagger, int root = 0);

}  // namespace cgdem::air_mpi
