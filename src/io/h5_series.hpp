// What a series of HDF5 snapshots with an XDMF index shares, whatever it holds (particles:
// SnapshotSeries, snapshot_series.hpp; air cells: GridSnapshotSeries, grid_snapshot_series.hpp):
// the folder, the file prefix (<dir>/<prefix>_<step:06>.h5, index <dir>/<prefix>.xdmf), the
// attributes written on every file, the compression level and the index.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/h5_util.hpp"
#include "io/particle_h5.hpp"
#include "io/xdmf_series.hpp"

namespace cgdem::io {

class H5Series {
 public:
  const std::string& xdmf_path() const { return index_.path(); }
  std::string snapshot_path(int64_t step) const;
  std::vector<int64_t> steps() const { return index_.steps(); }

 protected:
  // Checks the prefix, the attributes (none of the reserved names) and the compression level
  // (0..9, h5_options.hpp), and creates dir. `what` names the series in the error messages
  // ("snapshot", "grid snapshot").
  H5Series(std::string dir, std::string prefix, Attributes attributes, int compression, const char* what);
  // The steps of the snapshots already in dir, ascending (a resumed series indexes them again).
  std::vector<int64_t> existing_steps() const { return find_snapshot_steps(dir_, prefix_); }
  // A snapshot written to target's temporary file becomes snapshot `step`: the file is moved
  // into place, then the index gets grid_xml (the snapshot's <Grid> element) and is rewritten.
  void publish(AtomicTarget& target, int64_t step, std::string grid_xml);
  // Reads snapshot `step` back (resume) with HDF5's error printing off: returns
  // read(file, path, time), time the file's "time" attribute [s].
  template <class Read>
  auto read_back(int64_t step, Read&& read) const {
    h5::Quiet quiet;
    const std::string path = snapshot_path(step);
    h5::Id file = h5::open_file(path);
    const double time = h5::read_double_attribute(file, "time", path);
    return read(file, path, time);
  }

  std::string dir_, prefix_;
  Attributes attributes_;
  int compression_;
  XdmfTimeSeries index_;
};

}  // namespace cgdem::io
