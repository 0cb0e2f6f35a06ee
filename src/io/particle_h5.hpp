// Particles in HDF5 (snapshots, last_good.h5, exchange with Python/ParaView).
//
// Layout (SI units, native byte order); every dataset has the string attributes "units"
// and "description" (h5_util.hpp):
//   /particles/id      int64   [N]      parcel id, stable over the run          units "1"
//   /particles/species int32   [N]      species index (0 = first [[particles.species]])  "1"
//   /particles/x       float64 [N][3]   centre position (x, y, z)               "m"
//   /particles/v       float64 [N][3]   velocity, only if given                 "m/s"
//   /particles/omega   float64 [N][3]   angular velocity, only if given         "rad/s"
//   /particles/d       float64 [N]      parcel diameter (l d_O)                 "m"
//   /particles/vertex  int64   [N][1]   0 .. N-1: the XDMF Polyvertex connectivity "1"
//   attributes on "/": string key -> value from the caller (the resolved configuration
//                      "config" and "cgdem_revision", style.md habit 12); this module adds
//                      "cgdem_revision" (kGitRevision) when the caller has not, and a
//                      one-line "description"; with an Instant also "time" (float64),
//                      "time_units" = "s" and "step" (int64).
// Datasets are chunked and compressed (shuffle + deflate) at the given level (h5_options.hpp).
// The file is written to a temporary and renamed (atomic_file.hpp): readers never see a
// partial file, an interrupted write leaves the previous file intact.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "io/h5_options.hpp"
#include "io/particle_table.hpp"

namespace cgdem::io {

using Attributes = std::map<std::string, std::string>;

// The simulated instant a file holds: written as "time" [s] (+ "time_units") and "step".
struct Instant {
  double time = 0;
  int64_t step = 0;
};

void write_particles_h5(const std::string& path, const ParticleTable& table, const Attributes& attributes = {},
                        int compression = kDefaultCompression, std::optional<Instant> at = std::nullopt);

// Reads the table; if `attributes` is given it receives the string attributes of "/".
ParticleTable read_particles_h5(const std::string& path, Attributes* attributes = nullptr);

// The string attributes of "/" of any HDF5 file written by this module.
Attributes read_h5_attributes(const std::string& path);

namespace detail {
// File attributes every cgdem HDF5 file carries: the caller's strings, "cgdem_revision" if
// absent, "description"; then, with an instant, "time", "time_units", "step". Reserved:
// the caller may not pass "description", "time", "time_units" or "step".
void write_file_attributes(hid_t file, const Attributes& attributes, const std::string& description,
                           std::optional<Instant> at, const std::string& file_name);
// Error if `attributes` holds a key write_file_attributes writes itself.
void check_reserved_attributes(const Attributes& attributes, const char* what);
// Writes the /particles group into an open file (used by SnapshotSeries as well).
void write_particle_group(hid_t file, const ParticleTable& table, const std::string& file_name, int compression);
ParticleTable read_particle_group(hid_t file, const std::string& file_name);
}  // namespace detail

}  // namespace cgdem::io
