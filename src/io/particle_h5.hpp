// Particles in HDF5 (snapshots, checkpoints, exchange with Python/ParaView).
//
// Layout (SI units, native byte order):
//   /particles/id      int64   [N]
//   /particles/species int32   [N]
//   /particles/x       float64 [N][3]   position (m)
//   /particles/v       float64 [N][3]   velocity (m/s), only if given
//   /particles/omega   float64 [N][3]   angular velocity (rad/s), only if given
//   /particles/d       float64 [N]      diameter (m)
//   attributes on "/": string key -> value (the caller stores the resolved configuration
//                      and the git revision there, style.md habit 12)
// The file is written to a temporary and renamed (atomic_file.hpp): readers never see a
// partial file, an interrupted write leaves the previous file intact.
#pragma once
#include <hdf5.h>

#include <map>
#include <string>

#include "io/particle_table.hpp"

namespace cgdem::io {

using Attributes = std::map<std::string, std::string>;

void write_particles_h5(const std::string& path, const ParticleTable& table, const Attributes& attributes = {});

// Reads the table; if `attributes` is given it receives the string attributes of "/".
ParticleTable read_particles_h5(const std::string& path, Attributes* attributes = nullptr);

// The string attributes of "/" of any HDF5 file written by this module.
Attributes read_h5_attributes(const std::string& path);

namespace detail {
// Writes the /particles group into an open file (used by SnapshotSeries as well).
void write_particle_group(hid_t file, const ParticleTable& table, const std::string& file_name);
ParticleTable read_particle_group(hid_t file, const std::string& file_name);
}  // namespace detail

}  // namespace cgdem::io
