// XdmfTimeSeries: the XDMF 3 index of a series of HDF5 snapshots, one temporal collection
// that ParaView ("XDMF Reader", "Xdmf3 Reader S", "Xdmf3 Reader T"), meshio
// (meshio.xdmf.TimeSeriesReader) and h5py-based scripts open directly.
//
//   <Xdmf Version="3.0"><Domain><Grid GridType="Collection" CollectionType="Temporal">
//     <Grid Name="step_10" GridType="Uniform"> <Time Value="..."/> ... </Grid>  (one per snapshot)
//   </Grid></Domain></Xdmf>
//
// The elements are those of XDMF 2 and 3 alike (TopologyType, GeometryType, NumberType,
// HDF DataItems "file.h5:/path" relative to the index), so a reader of either version
// accepts it. The per-snapshot <Grid> elements are rendered by the series (particles or
// mesh) and kept by step. Time only moves forward: setting step s drops every entry with
// a later step (after a restart those belong to the abandoned run). The index file is
// rewritten atomically after every change, so it always lists exactly the committed
// snapshots.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cgdem::io {

class XdmfTimeSeries {
 public:
  XdmfTimeSeries(std::string path, std::string name) : path_(std::move(path)), name_(std::move(name)) {}

  // grid_xml: one complete <Grid ...>...</Grid> element (indented by the caller or not).
  void set(int64_t step, std::string grid_xml);
  std::string text() const;
  void write() const;  // atomic rewrite of path()
  const std::string& path() const { return path_; }
  std::vector<int64_t> steps() const;

 private:
  std::string path_, name_;
  std::map<int64_t, std::string> grids_;
};

// Helpers to render XDMF elements.
namespace xdmf {
std::string escape(const std::string& s);  // & < > " '
std::string number(double v);              // %.17g
// <DataItem Dimensions="dims" NumberType=.. Precision=.. Format="HDF">file:/dataset</DataItem>
std::string hdf_item(const std::string& dims, const char* number_type, int precision, const std::string& file,
                     const std::string& dataset);
// <Attribute Name=.. AttributeType=.. Center=..> item </Attribute>
std::string attribute(const std::string& name, const char* type, const char* center, const std::string& item);
}  // namespace xdmf

// `<prefix>_<step, at least 6 digits>.h5`, the snapshot file name (no directory).
std::string snapshot_file_name(const std::string& prefix, int64_t step);
// Steps of the files in `dir` named like snapshot_file_name(prefix, step), ascending.
std::vector<int64_t> find_snapshot_steps(const std::string& dir, const std::string& prefix);
// Checks that a series prefix / field name is usable in a file name / HDF5 path / XDMF name.
void check_series_name(const std::string& name, const char* what);

}  // namespace cgdem::io
