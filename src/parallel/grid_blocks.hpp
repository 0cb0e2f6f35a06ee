// The air grid cut into blocks of cells, one per MPI rank (issue 6, item 2 of
// docs/scale_out.md). No MPI here: a GridBlocks is plain data, the same on every rank.
//
// The global cell grid nx x ny x nz is cut along each axis a into p_a runs of cells,
//     run m = [lo_a(m), lo_a(m+1)),   lo_a(m) = floor(n_a m / p_a),
// so that run lengths differ by at most one cell. Ranks are numbered as in
// parallel::Decomposition, rank = i + px (j + py k), and the dims come from
// choose_block_dims (the rule of parallel::choose_dims on the grid's extent in cells: the
// least cut area), unless given.
//
// Faces: a block of n_a cells along a holds n_a + 1 faces normal to a (the MAC layout of
// fluid/mac_grid.hpp). On a cut the face between two blocks belongs to the UPPER block (it is
// its face 0); the lower block holds it as its face n_a, a ghost filled by the halo exchange.
// On a physical side the boundary face is the block's own, as in a serial run.
//
// The halo exchange needs every block to hold at least kGhost + 1 cells along each cut axis
// (the upper block sends its faces 0..kGhost down); the constructor checks it.
#pragma once
#include <array>
#include <vector>

#include "fluid/mac_grid.hpp"

namespace cgdem::air_mpi {

using Dims = std::array<int, 3>;

// The block counts px py pz = ranks with the least cut area sum_a (p_a - 1) A_a (A_a the
// grid's cross-section normal to a, in cells; parallel::choose_dims on the extent in
// cells): ties go to the larger px, then the larger py.
Dims choose_block_dims(int ranks, const std::array<int, 3>& cells);

class GridBlocks {
 public:
  // Dims from choose_dims(ranks, (nx, ny, nz)). Throws cgdem::Error for an empty grid,
  // ranks < 1, or blocks thinner than kGhost + 1 cells along a cut axis.
  GridBlocks(const std::array<int, 3>& global_cells, int ranks, int rank);
  GridBlocks(const std::array<int, 3>& global_cells, Dims dims, int rank);
  // Uneven blocks: starts[a] lists the first cell of every run along a, 0 = s_a(0) < s_a(1)
  // < ... < s_a(p_a) = n_a (p_a = starts[a].size() - 1), e.g. cuts balanced on the parcels.
  // Throws cgdem::Error when a list does not span the axis, does not increase, or leaves a
  // run shorter than kGhost + 1 cells (on a cut axis).
  using Starts = std::array<std::vector<int>, 3>;
  GridBlocks(const std::array<int, 3>& global_cells, const Starts& starts, int rank);

  const std::array<int, 3>& global_cells() const { return n_; }
  const Dims& dims() const { return dims_; }
  int ranks() const { return dims_[0] * dims_[1] * dims_[2]; }
  int rank() const { return rank_; }
  const Dims& coords() const { return coords_; }
  int rank_of(const Dims& c) const { return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]); }

  // This rank's cells: global indices [lo[a], hi[a]) along each axis.
  const std::array<int, 3>& lo() const { return lo_; }
  const std::array<int, 3>& hi() const { return hi_; }
  std::array<int, 3> local_cells() const { return {hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]}; }
  long local_count() const;
  // Start of run m along axis a (m = 0..p_a; run_start(a, p_a) = n_a).
  int run_start(int a, int m) const;

  // Rank across side s = 2 a + h (h = 0 low, 1 high; -x, +x, -y, +y, -z, +z), or -1 when that
  // side is on the domain boundary.
  int neighbour(int side) const { return nb_[side]; }
  bool is_cut(int side) const { return nb_[side] >= 0; }

  // The local air grid of this rank: its cells, dx, and origin shifted to its first cell.
  fluid::MacGrid local_grid(const fluid::MacGrid& global) const;

 private:
  void init(int rank);

  std::array<int, 3> n_;
  Dims dims_;
  Starts starts_;  // empty: the even runs floor(n_a m / p_a)
  int rank_ = 0;
  Dims coords_{};
  std::array<int, 3> lo_{}, hi_{};
  std::array<int, 6> nb_{};
};

// This block's entries of a packed global array, x fastest (the layout of the serial
// pressure solver, pressure_solver.hpp): cells for stagger < 0, else the faces normal to
// axis `stagger`, lo .. hi along it (the cut face included), cells across.
std::vector<double> block_part(const GridBlocks& b, const std::vector<double>& global, int stagger);

}  // namespace cgdem::air_mpi
