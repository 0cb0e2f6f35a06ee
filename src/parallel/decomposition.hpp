// Block decomposition of an axis-aligned box over MPI ranks (issue 6, docs/scale_out.md).
//
// The box [lo, hi] is cut into px x py x pz blocks of equal size, one per rank:
//     rank = i + px (j + py k),   0 <= i < px, 0 <= j < py, 0 <= k < pz,
//     block (i, j, k) = [c_x(i), c_x(i+1)) x [c_y(j), c_y(j+1)) x [c_z(k), c_z(k+1)),
//     c_a(m) = lo_a + (hi_a - lo_a) m / p_a,
// each interval half-open except the last, which includes hi_a: every point of the box has
// exactly one owner, and owner_of() agrees with block() to the last bit (it tests the
// point against the same cut values, not only its rounded quotient).
//
// Neighbours of a rank are the ranks whose blocks touch its own through a face, an edge or
// a corner (up to 26): the ranks a parcel can move to within one migration, and later the
// ranks that exchange ghost parcels and air halos. On a periodic axis the blocks wrap
// around; a rank is then listed once however many sides it touches (px = 2) and never as
// its own neighbour (px = 1: the periodic image is local, handled by NeighborList).
//
// No MPI here: a Decomposition is plain data, the same on every rank.
#pragma once
#include <array>
#include <vector>

#include "core/vec3.hpp"
#include "geometry/shape.hpp"
#include "particles/neighbor_list.hpp"

namespace cgdem::parallel {

using Dims = std::array<int, 3>;

class Decomposition {
 public:
  // Throws cgdem::Error for an empty or non-finite box or a non-positive count of blocks.
  Decomposition(const geometry::Aabb& box, Dims dims, std::array<bool, 3> periodic = {false, false, false});
  // Uneven blocks: cuts[a] lists c_a(0) = box.lo_a < c_a(1) < ... < c_a(p_a) = box.hi_a
  // (load balance: balanced_cuts()). Throws cgdem::Error when a list does not span the box
  // or does not increase strictly.
  using Cuts = std::array<std::vector<double>, 3>;
  Decomposition(const geometry::Aabb& box, const Cuts& cuts, std::array<bool, 3> periodic = {false, false, false});
  const Cuts& cuts() const { return cut_; }
  // The narrowest block along any axis [m] (a block must be wider than one interaction
  // range, so that a parcel's ghosts and moves reach only the neighbouring ranks).
  double narrowest_block() const;

  const geometry::Aabb& box() const { return box_; }
  const Dims& dims() const { return dims_; }
  const std::array<bool, 3>& periodic() const { return wrap_.axis; }
  int ranks() const { return dims_[0] * dims_[1] * dims_[2]; }

  int rank_of(const Dims& c) const { return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]); }
  Dims coords_of(int rank) const;

  // The rank whose block holds x. Off the box, x is wrapped on periodic axes and clamped
  // onto the box on the others (NaN goes to the first block): callers that must not
  // accept such points test contains() first.
  int owner_of(const Vec3& x) const;
  // x lies in the box on every non-periodic axis (false for NaN).
  bool contains(const Vec3& x) const;
  // The block of a rank (closed box; see the header comment for which faces it owns).
  geometry::Aabb block(int rank) const;
  // Neighbour ranks of `rank`, in increasing order, without duplicates or `rank` itself.
  std::vector<int> neighbours(int rank) const;

 private:
  int index_along(int a, double x) const;

  geometry::Aabb box_;
  Dims dims_;
  Periodicity wrap_;  // the box on the periodic axes
  std::array<std::vector<double>, 3> cut_;  // cut_[a][m] = c_a(m), m = 0..p_a
  bool uniform_ = true;                     // equal blocks: index_along() may guess by division
};

// The block counts (px, py, pz), px py pz = n_ranks, whose cuts through a box of this
// extent have the least total area, sum_a (p_a - 1) A_a with A_a the box's cross-section
// normal to axis a: the least sum of block surfaces, hence of halo cells and ghost parcels
// for a uniform load. Like MPI_Dims_create, but weighted by the box's shape (a flat box is
// not cut across its thickness). Ties go to the larger px, then the larger py.
// Throws cgdem::Error for n_ranks < 1 or an extent that is not positive.
Dims choose_dims(int n_ranks, const Vec3& extent);

// Cuts for dims blocks of the box that share out the points (parcel centres, or any cost
// samples) evenly: along each axis with p_a > 1 blocks, the cuts sit at the quantiles
// m / p_a of the points' coordinates (each axis on its own: even shares for cuts along one
// axis, close to even for a product of axes when the coordinates are nearly independent).
// No block is narrower than min_width [m] (one interaction range): quantiles that would
// make one are moved apart, and a box too small for p_a blocks of min_width throws
// cgdem::Error. Without points the cuts are even.
Decomposition::Cuts balanced_cuts(const geometry::Aabb& box, Dims dims, const std::vector<Vec3>& points,
                                  double min_width);

}  // namespace cgdem::parallel
