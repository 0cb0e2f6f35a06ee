// Gridded fields of a run for the reduced-order comparison: snapshots in time of
//   * the solid fraction phi_s = 1 - eps, from the air snapshots (air_*.h5, cell field eps)
//     when the run has air, else deposited from the particle snapshots (particles_*.h5) on
//     the study grid by the trilinear (cloud-in-cell) kernel
//       phi_s(c) = sum_p V_p W(x_p - x_c) / dx^3,  W = prod_a max(0, 1 - |dx_a| / dx)   (F1)
//     which conserves volume exactly (the weights of a parcel sum to 1; a weight that
//     falls outside the grid is wrapped on a periodic axis and clipped to the nearest
//     cell on the others);
//   * the air pressure p (air_*.h5, cell field p) when the run has air.
// Every run of a study uses the same grid, so the fields are vectors of the same space.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "io/particle_table.hpp"

namespace cgdem::scaling {

struct Grid {
  Vec3 origin;  // lower corner, m
  double dx = 0;  // cell size, m
  int nx = 0, ny = 0, nz = 0;
  std::array<bool, 3> periodic{false, false, false};
  long cells() const { return static_cast<long>(nx) * ny * nz; }
};

// The grid of cells of size dx covering [lo, hi] (rounded up to whole cells).
Grid grid_over(Vec3 lo, Vec3 hi, double dx, std::array<bool, 3> periodic);

// (F1): solid fraction of each cell, flat index i + nx (j + ny k).
std::vector<double> solid_fraction(const io::ParticleTable& t, const Grid& g);

struct Frame {
  double t = 0;
  std::string file;
};
// Snapshots <dir>/<prefix>_NNNNNN.h5 with their "time" attribute, ascending in time
// (read through io/air_snapshot_reader.hpp, for particle and air snapshots alike).
std::vector<Frame> list_frames(const std::string& dir, const std::string& prefix);

// One scalar cell field of an air snapshot (x fastest, io::read_air_snapshot); `g`, when
// given, receives its grid (dx: the spacing along x). Throws cgdem::Error naming the file
// and the field (an unknown name lists the file's fields).
std::vector<double> read_cell_field(const std::string& file, const std::string& name, Grid* g);

}  // namespace cgdem::scaling
