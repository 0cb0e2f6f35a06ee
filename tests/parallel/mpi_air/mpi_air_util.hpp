// Shared helpers of the multi-rank air tests (one process per rank, MPI_COMM_WORLD).
#pragma once
#include <mpi.h>

#include <vector>

#include "../mpi_util.hpp"
#include "parallel/grid_blocks.hpp"

namespace cgdem::air_mpi::test {

using cgdem::test::maxed;
using cgdem::test::summed;
using cgdem::test::world_rank;
using cgdem::test::world_size;

// The cuts every test runs on: 1 rank 1 x 1 x 1, 2 ranks choose_dims (2 x 1 x 1 for these
// grids), 4 ranks both 2 x 2 x 1 and 4 x 1 x 1.
inline std::vector<GridBlocks> layouts(const std::array<int, 3>& n) {
  const int size = world_size(), rank = world_rank();
  if (size == 4) return {GridBlocks(n, Dims{2, 2, 1}, rank), GridBlocks(n, Dims{4, 1, 1}, rank)};
  return {GridBlocks(n, size, rank)};
}

}  // namespace cgdem::air_mpi::test
