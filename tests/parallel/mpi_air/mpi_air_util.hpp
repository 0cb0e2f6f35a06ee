// Shared helpers of the multi-rank air tests (one process per rank, MPI_COMM_WORLD).
#pragma once
#include <mpi.h>

#include <vector>

#include "air_mpi/grid_blocks.hpp"

namespace cgdem::air_mpi::test {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int world_size() {
  int s = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}
inline long summed(long v) {
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return v;
}
inline double maxed(double v) {
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return v;
}

// The cuts every test runs on: 1 rank 1 x 1 x 1, 2 ranks choose_dims (2 x 1 x 1 for these
// grids), 4 ranks both 2 x 2 x 1 and 4 x 1 x 1.
inline std::vector<GridBlocks> layouts(const std::array<int, 3>& n) {
  const int size = world_size(), rank = world_rank();
  if (size == 4) return {GridBlocks(n, Dims{2, 2, 1}, rank), GridBlocks(n, Dims{4, 1, 1}, rank)};
  return {GridBlocks(n, size, rank)};
}

}  // namespace cgdem::air_mpi::test
