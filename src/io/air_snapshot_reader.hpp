// Reading back the snapshots a run writes, for the analysis commands (cgdem scale), without
// the HDF5 API in their includes. The formats are those of the writers:
//   particles_<step>.h5  snapshot_series.hpp (the particle table: read_particles_h5 in
//                        particle_h5.hpp)
//   air_<step>.h5        grid_snapshot_series.hpp: /grid/n int64[3], /grid/origin and
//                        /grid/spacing float64[3] (x, y, z), /cells/<name> float64
//                        [nz][ny][nx] (scalars) or [nz][ny][nx][3] (vectors), attributes
//                        "time" (s) and "step" on "/"
// Cell (i, j, k) of a field is at flat index i + nx (j + ny k) (x fastest), as written.
// Values are read as stored (no conversion beyond HDF5's native double), so a snapshot
// read back equals what was written bit for bit. Every error names the file and the
// object; a missing field lists the fields the file has.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace cgdem::io {

// The "time" attribute (s) of any snapshot file (particles_*.h5 or air_*.h5).
double read_snapshot_time(const std::string& path);

struct AirGrid {
  std::array<int64_t, 3> n{};  // cells along x, y, z
  Vec3 origin;                 // lower corner, m
  Vec3 spacing;                // cell size along x, y, z, m
  size_t cells() const { return static_cast<size_t>(n[0] * n[1] * n[2]); }
};

struct AirSnapshot {
  double time = 0;  // s
  int64_t step = 0;
  AirGrid grid;
  std::map<std::string, std::vector<double>> scalars;                 // name -> cells() values
  std::map<std::string, std::array<std::vector<double>, 3>> vectors;  // name -> x, y, z components
};

// The mesh of an air snapshot. Error on a missing or malformed /grid (not 3 values, a
// count < 1, a spacing <= 0).
AirGrid read_air_grid(const std::string& path);

// The names of the cell fields of an air snapshot (scalars and vectors), in name order.
std::vector<std::string> air_field_names(const std::string& path);

// Time, step, mesh and the named cell fields (every field when `fields` is empty). Error
// on an unknown name (listing the file's fields) or a field whose shape does not match
// the mesh.
AirSnapshot read_air_snapshot(const std::string& path, const std::vector<std::string>& fields = {});

}  // namespace cgdem::io
