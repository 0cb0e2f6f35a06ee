#include "io/air_snapshot_reader.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "io/h5_util.hpp"

namespace cgdem::io {
namespace {

std::string shape(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? "," : "") + std::to_string(dims[i]);
  return s + "]";
}

std::string fail_prefix(const std::string& path) { return "HDF5 file '" + path + "': "; }

AirGrid read_grid_group(hid_t file, const std::string& path) {
  if (!h5::exists(file, "grid")) throw Error(fail_prefix(path) + "no group '/grid' (not an air snapshot?)");
  std::vector<hsize_t> dims;
  const std::vector<int64_t> n = h5::read_int64(file, "grid/n", dims, path);
  const std::vector<double> o = h5::read_double(file, "grid/origin", dims, path);
  const std::vector<double> h = h5::read_double(file, "grid/spacing", dims, path);
  if (n.size() != 3 || o.size() != 3 || h.size() != 3)
    throw Error(fail_prefix(path) + "/grid/n, /grid/origin and /grid/spacing must hold 3 values each");
  if (std::min({n[0], n[1], n[2]}) < 1) throw Error(fail_prefix(path) + "/grid/n has a count < 1");
  if (!(h[0] > 0 && h[1] > 0 && h[2] > 0)) throw Error(fail_prefix(path) + "/grid/spacing has a value <= 0");
  AirGrid g;
  g.n = {n[0], n[1], n[2]};
  g.origin = {o[0], o[1], o[2]};
  g.spacing = {h[0], h[1], h[2]};
  return g;
}

std::vector<std::string> cell_field_names(hid_t file, const std::string& path) {
  if (!h5::exists(file, "cells")) throw Error(fail_prefix(path) + "no group '/cells' (not an air snapshot?)");
  h5::Id cells(H5Gopen2(file, "cells", H5P_DEFAULT), H5Gclose);
  if (cells.get() < 0) throw Error(fail_prefix(path) + "cannot open '/cells'");
  return h5::members(cells, path);
}

// Reads /cells/<name> into `out` as a scalar or a vector field after checking its shape.
void read_field(hid_t file, const std::string& path, const AirGrid& g, const std::string& name, AirSnapshot& out) {
  std::vector<hsize_t> dims;
  std::vector<double> v = h5::read_double(file, "cells/" + name, dims, path);
  const std::vector<hsize_t> zyx = {static_cast<hsize_t>(g.n[2]), static_cast<hsize_t>(g.n[1]),
                                    static_cast<hsize_t>(g.n[0])};
  std::vector<hsize_t> zyx3 = zyx;
  zyx3.push_back(3);
  if (dims == zyx) {
    out.scalars[name] = std::move(v);
    return;
  }
  if (dims != zyx3)
    throw Error(fail_prefix(path) + "'/cells/" + name + "' has shape " + shape(dims) + ", expected " + shape(zyx) +
                " or " + shape(zyx3) + " for the grid in /grid/n");
  auto& comp = out.vectors[name];
  for (int k = 0; k < 3; ++k) comp[k].resize(g.cells());
  for (size_t c = 0; c < g.cells(); ++c)
    for (int k = 0; k < 3; ++k) comp[k][c] = v[3 * c + k];
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

}  // namespace

double read_snapshot_time(const std::string& path) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  return h5::read_double_attribute(file, "time", path);
}

AirGrid read_air_grid(const std::string& path) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  return read_grid_group(file, path);
}

std::vector<std::string> air_field_names(const std::string& path) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  return cell_field_names(file, path);
}

AirSnapshot read_air_snapshot(const std::string& path, const std::vector<std::string>& fields) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  AirSnapshot s;
  s.time = h5::read_double_attribute(file, "time", path);
  s.step = static_cast<int64_t>(h5::read_double_attribute(file, "step", path));
  s.grid = read_grid_group(file, path);
  const std::vector<std::string> have = cell_field_names(file, path);
  for (const std::string& name : fields)
    if (std::find(have.begin(), have.end(), name) == have.end())
      throw Error(fail_prefix(path) + "no cell field '" + name + "' (it has " + joined(have) + ")");
  for (const std::string& name : fields.empty() ? have : fields) read_field(file, path, s.grid, name, s);
  return s;
}

}  // namespace cgdem::io
