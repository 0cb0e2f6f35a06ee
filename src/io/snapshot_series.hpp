// SnapshotSeries: particle snapshots over time, one HDF5 file per output step plus an XDMF
// index that ParaView opens directly.
//
//   <dir>/<prefix>_<step:06>.h5   /particles/... as in particle_h5.hpp,
//                                 /fields/<name> float64 [N] extra per-particle scalars,
//                                 attributes on "/": the series attributes (strings: config,
//                                 cgdem_revision, ...) + "description" + "time" (float64) +
//                                 "time_units" ("s") + "step" (int64); every dataset has
//                                 "units" and "description"; datasets chunked and compressed
//                                 at the series' level (h5_options.hpp)
//   <dir>/<prefix>.xdmf           XDMF 3 temporal collection of all snapshots: Polyvertex
//                                 topology of N elements with its connectivity
//                                 (/particles/vertex), XYZ geometry from /particles/x, node
//                                 attributes "velocity", "omega" (vectors, when given),
//                                 "position" (the geometry again, for readers that keep the
//                                 first step's points: meshio's TimeSeriesReader), "diameter",
//                                 "id", "species" and every extra field under its own name.
// Both files are written atomically; the index is rewritten after each snapshot.
// Restart: with resume = true the snapshots already in <dir> are indexed again, and the
// first write(step) drops later ones from the index (they belong to the abandoned run).
// The mesh counterpart (air phase) is GridSnapshotSeries in grid_snapshot_series.hpp.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/h5_series.hpp"
#include "io/particle_h5.hpp"

namespace cgdem::io {

using ScalarFields = std::map<std::string, std::vector<double>>;

class SnapshotSeries : public H5Series {
 public:
  // compression: 0..9 (h5_options.hpp).
  SnapshotSeries(std::string dir, std::string prefix, Attributes attributes, bool resume = false,
                 int compression = kDefaultCompression);

  // Writes one snapshot and rewrites the index; returns the snapshot's path (snapshot_path,
  // xdmf_path and steps: H5Series).
  // Every extra field has one value per particle and an entry in `info` (its units and
  // description); names must not be reserved (velocity, omega, position, diameter, id,
  // species).
  std::string write(int64_t step, double time, const ParticleTable& table, const ScalarFields& extra = {},
                    const FieldInfos& info = {});

 private:
  struct Entry {
    int64_t step = 0;
    double time = 0;
    size_t n = 0;
    bool has_v = false, has_omega = false;
    std::vector<std::string> fields;
    bool has_vertex = true;  // false for snapshots written before /particles/vertex existed
  };
  std::string render(const Entry& e) const;
  Entry read_entry(int64_t step) const;  // metadata of an existing snapshot (resume)
};

}  // namespace cgdem::io
