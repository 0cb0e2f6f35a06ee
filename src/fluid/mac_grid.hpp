// Uniform Cartesian staggered (MAC) grid of the air phase and its padded field arrays.
//
// Cells (i, j, k), 0 <= i < nx etc., have centres  x_c = origin + (i + 1/2, j + 1/2, k + 1/2) dx.
// Scalars (p, eps, alpha) live at cell centres. The velocity component along axis d lives on
// the d-faces: u(i,j,k) at origin + (i, j + 1/2, k + 1/2) dx, 0 <= i <= nx; the face d-index
// `i` sits between cells i-1 and i. Cells are cubes of edge dx (SI, metres).
//
// Every Field carries `kGhost` ghost layers on each side so that the advection stencil
// (TVD, 4 points) and the viscous stencil can read neighbours without branches. Ghosts are
// written only by the explicit fill functions of boundary.hpp (the future MPI halo exchange).
#pragma once
#include <algorithm>
#include <array>
#include <vector>

#include "core/error.hpp"
#include "core/vec3.hpp"

namespace cgdem::fluid {

inline constexpr int kGhost = 2;
// Loops over fewer points than this run serially: on small grids thread start-up and
// barriers cost more than the work (results never depend on the thread count).
inline constexpr long kOmpMinWork = 32768;

struct MacGrid {
  int nx = 0, ny = 0, nz = 0;
  double dx = 1;      // cell edge [m]
  Vec3 origin{};      // lower corner of the domain [m]

  void validate() const {
    if (nx < 1 || ny < 1 || nz < 1) throw Error("fluid grid: nx, ny, nz must be >= 1");
    if (!(dx > 0)) throw Error("fluid grid: dx must be > 0");
  }
  std::array<int, 3> n() const { return {nx, ny, nz}; }
  long cells() const { return static_cast<long>(nx) * ny * nz; }
  Vec3 cell_centre(int i, int j, int k) const {
    return origin + dx * Vec3{i + 0.5, j + 0.5, k + 0.5};
  }
  // Centre of the d-face with index (i, j, k) in the layout of component d.
  Vec3 face_centre(int d, int i, int j, int k) const {
    Vec3 x = cell_centre(i, j, k);
    x[d] -= 0.5 * dx;
    return x;
  }
  // Interior extents of component d's face array (n+1 along d).
  std::array<int, 3> face_extent(int d) const {
    std::array<int, 3> e = n();
    e[d] += 1;
    return e;
  }
};

// Dense 3-D array with kGhost ghost layers; index (i, j, k) with -kGhost <= i < ni + kGhost.
class Field {
 public:
  Field() = default;
  Field(int ni, int nj, int nk, double value = 0.0) { resize(ni, nj, nk, value); }
  explicit Field(std::array<int, 3> e, double value = 0.0) { resize(e[0], e[1], e[2], value); }

  void resize(int ni, int nj, int nk, double value = 0.0) {
    ni_ = ni, nj_ = nj, nk_ = nk;
    sy_ = ni + 2 * kGhost;
    sz_ = static_cast<long>(sy_) * (nj + 2 * kGhost);
    data_.assign(static_cast<size_t>(sz_) * (nk + 2 * kGhost), value);
  }
  bool empty() const { return data_.empty(); }
  size_t size() const { return data_.size(); }  // entries, ghost layers included
  int ni() const { return ni_; }
  int nj() const { return nj_; }
  int nk() const { return nk_; }
  std::array<int, 3> extent() const { return {ni_, nj_, nk_}; }
  long index(int i, int j, int k) const { return (i + kGhost) + sy_ * (j + kGhost) + sz_ * (k + kGhost); }
  // Offset in memory of one step along axis d.
  long stride(int d) const { return d == 0 ? 1 : (d == 1 ? sy_ : sz_); }
  double& operator()(int i, int j, int k) { return data_[index(i, j, k)]; }
  double operator()(int i, int j, int k) const { return data_[index(i, j, k)]; }
  double* data() { return data_.data(); }
  const double* data() const { return data_.data(); }
  void fill(double v) { std::fill(data_.begin(), data_.end(), v); }

 private:
  int ni_ = 0, nj_ = 0, nk_ = 0;
  long sy_ = 0, sz_ = 0;
  std::vector<double> data_;
};

// Cell-centred field and the three face fields of a grid.
inline Field make_cell_field(const MacGrid& g, double v = 0.0) { return Field(g.n(), v); }
inline Field make_face_field(const MacGrid& g, int d, double v = 0.0) { return Field(g.face_extent(d), v); }

// Unit offsets along an axis, for writing stencils once for all three components.
inline std::array<int, 3> unit(int d) { return {d == 0, d == 1, d == 2}; }

}  // namespace cgdem::fluid
