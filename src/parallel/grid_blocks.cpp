// Blocks of the air grid; see grid_blocks.hpp.
#include "parallel/grid_blocks.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "parallel/decomposition.hpp"

namespace cgdem::air_mpi {

namespace {
void check_grid(const std::array<int, 3>& n) {
  if (n[0] < 1 || n[1] < 1 || n[2] < 1)
    throw Error(fmt::format("air blocks: the grid needs at least one cell per axis (got {} x {} x {})", n[0], n[1], n[2]));
}
}  // namespace

Dims choose_block_dims(int ranks, const std::array<int, 3>& n) {
  if (ranks < 1) throw Error(fmt::format("air blocks: need at least one rank (got {})", ranks));
  // parallel::choose_dims on the grid's extent in cells (the areas are then cell counts).
  return parallel::choose_dims(ranks, Vec3{double(n[0]), double(n[1]), double(n[2])});
}

GridBlocks::GridBlocks(const std::array<int, 3>& global_cells, int ranks, int rank) : n_(global_cells) {
  check_grid(n_);
  dims_ = choose_block_dims(ranks, n_);
  init(rank);
}

GridBlocks::GridBlocks(const std::array<int, 3>& global_cells, Dims dims, int rank) : n_(global_cells), dims_(dims) {
  check_grid(n_);
  if (dims_[0] < 1 || dims_[1] < 1 || dims_[2] < 1)
    throw Error(fmt::format("air blocks: block counts must be >= 1 (got {} x {} x {})", dims_[0], dims_[1], dims_[2]));
  init(rank);
}

GridBlocks::GridBlocks(const std::array<int, 3>& global_cells, const Starts& starts, int rank)
    : n_(global_cells), starts_(starts) {
  check_grid(n_);
  for (int a = 0; a < 3; ++a) {
    const auto& s = starts_[a];
    if (s.size() < 2 || s.front() != 0 || s.back() != n_[a])
      throw Error(fmt::format("air blocks: the run starts along {} must go from 0 to {} cells", "xyz"[a], n_[a]));
    dims_[a] = static_cast<int>(s.size()) - 1;
    for (size_t m = 1; m < s.size(); ++m)
      if (s[m] - s[m - 1] < (dims_[a] > 1 ? fluid::kGhost + 1 : 1))
        throw Error(fmt::format("air blocks: run {} along {} has {} cells (cells {} .. {}); a block needs at least {} "
                                "(kGhost + 1) along a cut axis",
                                m - 1, "xyz"[a], s[m] - s[m - 1], s[m - 1], s[m], fluid::kGhost + 1));
  }
  init(rank);
}

int GridBlocks::run_start(int a, int m) const {
  if (!starts_[a].empty()) return starts_[a][m];
  return static_cast<int>(static_cast<long>(n_[a]) * m / dims_[a]);
}

long GridBlocks::local_count() const {
  const auto e = local_cells();
  return static_cast<long>(e[0]) * e[1] * e[2];
}

void GridBlocks::init(int rank) {
  if (rank < 0 || rank >= ranks())
    throw Error(fmt::format("air blocks: rank {} outside 0..{}", rank, ranks() - 1));
  rank_ = rank;
  coords_ = {rank % dims_[0], (rank / dims_[0]) % dims_[1], rank / (dims_[0] * dims_[1])};
  for (int a = 0; a < 3; ++a) {
    if (starts_[a].empty() && dims_[a] > 1 && n_[a] / dims_[a] < fluid::kGhost + 1)
      throw Error(fmt::format("air blocks: {} blocks along axis {} leave fewer than {} cells per block of {} "
                              "(the halo exchange needs kGhost + 1 = {})",
                              dims_[a], "xyz"[a], fluid::kGhost + 1, n_[a], fluid::kGhost + 1));
    lo_[a] = run_start(a, coords_[a]);
    hi_[a] = run_start(a, coords_[a] + 1);
    for (int h = 0; h < 2; ++h) {
      Dims c = coords_;
      c[a] += h ? 1 : -1;
      nb_[2 * a + h] = (c[a] < 0 || c[a] >= dims_[a]) ? -1 : rank_of(c);
    }
  }
}

fluid::MacGrid GridBlocks::local_grid(const fluid::MacGrid& global) const {
  if (global.n() != n_)
    throw Error(fmt::format("air blocks: grid of {} x {} x {} cells given to blocks of {} x {} x {}", global.nx,
                            global.ny, global.nz, n_[0], n_[1], n_[2]));
  fluid::MacGrid g = global;
  const auto e = local_cells();
  g.nx = e[0], g.ny = e[1], g.nz = e[2];
  g.origin = global.origin + global.dx * Vec3{double(lo_[0]), double(lo_[1]), double(lo_[2])};
  return g;
}

std::vector<double> block_part(const GridBlocks& b, const std::vector<double>& global, int stagger) {
  auto e = b.local_cells();
  auto ge = b.global_cells();
  if (stagger >= 0) e[stagger] += 1, ge[stagger] += 1;
  if (static_cast<long>(global.size()) != long(ge[0]) * ge[1] * ge[2])
    throw Error(fmt::format("air blocks: a global array of {} entries, the grid's has {}", global.size(),
                            long(ge[0]) * ge[1] * ge[2]));
  std::vector<double> out(long(e[0]) * e[1] * e[2]);
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i)
        out[i + long(e[0]) * (j + long(e[1]) * k)] =
            global[(b.lo()[0] + i) + long(ge[0]) * ((b.lo()[1] + j) + long(ge[1]) * (b.lo()[2] + k))];
  return out;
}

}  // namespace cgdem::air_mpi
