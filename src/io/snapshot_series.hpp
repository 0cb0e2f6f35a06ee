// SnapshotSeries: particle snapshots over time, one HDF5 file per output step plus an XDMF
// index that ParaView opens directly.
//
//   <dir>/<prefix>_<step:06>.h5   /particles/... as in particle_h5.hpp,
//                                 /fields/<name> float64 [N] extra per-particle scalars,
//                                 attributes on "/": the series attributes (strings: config,
//                                 revision, ...) + "time" (float64, s) + "step" (int64)
//   <dir>/<prefix>.xdmf           temporal collection of all snapshots: Polyvertex topology,
//                                 XYZ geometry from /particles/x, node attributes "velocity",
//                                 "omega" (vectors, when given), "diameter", "id", "species" and
//                                 every extra field under its own name.
// Both files are written atomically; the index is rewritten after each snapshot.
// Restart: with resume = true the snapshots already in <dir> are indexed again, and the
// first write(step) drops later ones from the index (they belong to the abandoned run).
// The mesh counterpart (air phase) is GridSnapshotSeries in grid_snapshot_series.hpp.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/particle_h5.hpp"
#include "io/xdmf_series.hpp"

namespace cgdem::io {

using ScalarFields = std::map<std::string, std::vector<double>>;

class SnapshotSeries {
 public:
  SnapshotSeries(std::string dir, std::string prefix, Attributes attributes, bool resume = false);

  // Writes one snapshot and rewrites the index; returns the snapshot's path.
  // Every extra field has one value per particle; names must not be reserved
  // (velocity, omega, diameter, id, species).
  std::string write(int64_t step, double time, const ParticleTable& table, const ScalarFields& extra = {});

  const std::string& xdmf_path() const { return index_.path(); }
  std::string snapshot_path(int64_t step) const;
  std::vector<int64_t> steps() const { return index_.steps(); }

 private:
  struct Entry {
    int64_t step = 0;
    double time = 0;
    size_t n = 0;
    bool has_v = false, has_omega = false;
    std::vector<std::string> fields;
  };
  std::string render(const Entry& e) const;
  Entry read_entry(int64_t step) const;  // metadata of an existing snapshot (resume)

  std::string dir_, prefix_;
  Attributes attributes_;
  XdmfTimeSeries index_;
};

}  // namespace cgdem::io
