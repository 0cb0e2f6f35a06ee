#include "io/grid_snapshot_series.hpp"

#include <filesystem>
#include <set>

#include "io/atomic_file.hpp"
#include "io/h5_util.hpp"

namespace cgdem::io {

const FieldInfo* air_field_info(const std::string& name) {
  static const FieldInfos known = {
      {"eps", {"1", "air volume fraction (void fraction) of the cell: 1 minus the parcels' volume fraction"}},
      {"p",
       {"Pa", "air pressure at the cell centre, relative to the still air's pressure on the top plane "
              "(air.boundary.open_pressure, 0 by default); it includes the hydrostatic part"}},
      {"alpha", {"1", "wall fraction of the cell (immersed boundary): 0 all fluid, 1 inside a wall"}},
      {"u",
       {"m/s", "interstitial air velocity (x, y, z) at the cell centre: mean of the two MAC face values of each "
               "component"}}};
  auto it = known.find(name);
  return it == known.end() ? nullptr : &it->second;
}

namespace {

// A cell field's units and description: from write()'s `info`, else air_field_info().
const FieldInfo& field_info(const FieldInfos& info, const std::string& name, const std::string& path) {
  auto it = info.find(name);
  if (it != info.end()) return it->second;
  if (const FieldInfo* known = air_field_info(name)) return *known;
  throw Error(path + ": grid field '" + name + "' has no units and description");
}

// The cell fields of write() checked (a valid name with units and description, each name
// once across scalars and vectors, ncell values per array); their names, in map order, into
// scalar_names and vector_names.
void check_fields(const std::string& path, size_t ncell, const CellScalars& scalars, const CellVectors& vectors,
                  const FieldInfos& info, std::vector<std::string>& scalar_names,
                  std::vector<std::string>& vector_names) {
  std::set<std::string> names;
  auto check_field = [&](const std::string& name, size_t size) {
    check_series_name(name, "grid field name");
    field_info(info, name, path);
    if (!names.insert(name).second) throw Error(path + ": grid field '" + name + "' given twice");
    if (size != ncell)
      throw Error(path + ": grid field '" + name + "' has " + std::to_string(size) + " values for " +
                  std::to_string(ncell) + " cells");
  };
  for (const auto& [name, v] : scalars) check_field(name, v.size()), scalar_names.push_back(name);
  for (const auto& [name, v] : vectors) {
    for (const auto& comp : v) check_field(name, comp.size()), names.erase(name);
    names.insert(name);
    vector_names.push_back(name);
  }
}

}  // namespace

GridSnapshotSeries::GridSnapshotSeries(std::string dir, std::string prefix, Attributes attributes, bool resume,
                                       int compression)
    : H5Series(std::move(dir), std::move(prefix), std::move(attributes), compression, "grid snapshot") {
  if (resume)
    for (int64_t s : existing_steps()) index_.set(s, render(read_entry(s)));
}

std::string GridSnapshotSeries::write(int64_t step, double time, int nx, int ny, int nz, Vec3 origin, Vec3 spacing,
                                      const CellScalars& scalars, const CellVectors& vectors,
                                      const FieldInfos& info) {
  h5::Quiet quiet;
  const std::string path = snapshot_path(step);
  if (nx < 1 || ny < 1 || nz < 1)
    throw Error(path + ": grid must have at least one cell per direction, got " + std::to_string(nx) + "x" +
                std::to_string(ny) + "x" + std::to_string(nz));
  if (!(spacing.x > 0 && spacing.y > 0 && spacing.z > 0)) throw Error(path + ": grid spacing must be > 0");
  const size_t ncell = static_cast<size_t>(nx) * ny * nz;
  Entry e{step, time, {nx, ny, nz}, origin, spacing, {}, {}};
  check_fields(path, ncell, scalars, vectors, info, e.scalars, e.vectors);
  auto info_of = [&](const std::string& name) -> const FieldInfo& { return field_info(info, name, path); };

  const hsize_t Z = nz, Y = ny, X = nx;
  AtomicTarget target(path);
  {
    h5::Id file = h5::create_file(target.tmp_path(), path);
    detail::write_file_attributes(file, attributes_,
                                  "cgdem air snapshot: cell-centred fields on a uniform grid, SI units; "
                                  "/cells/<field>[k][j][i] is cell (i, j, k), x fastest",
                                  Instant{time, step}, path);
    h5::Id grid = h5::create_group(file, "grid", path);
    const int64_t n[3] = {nx, ny, nz};
    const double o[3] = {origin.x, origin.y, origin.z}, h[3] = {spacing.x, spacing.y, spacing.z};
    h5::write(grid, "n", {3}, n, path, {"1", "number of cells along x, y, z"}, compression_);
    h5::write(grid, "origin", {3}, o, path, {"m", "lower corner of the grid (x, y, z)"}, compression_);
    h5::write(grid, "spacing", {3}, h, path, {"m", "cell size along x, y, z"}, compression_);
    h5::Id cells = h5::create_group(file, "cells", path);
    for (const auto& [name, v] : scalars) h5::write(cells, name, {Z, Y, X}, v.data(), path, info_of(name), compression_);
    std::vector<double> packed(3 * ncell);
    for (const auto& [name, v] : vectors) {
      for (size_t c = 0; c < ncell; ++c)
        for (int k = 0; k < 3; ++k) packed[3 * c + k] = v[k][c];
      h5::write(cells, name, {Z, Y, X, 3}, packed.data(), path, info_of(name), compression_);
    }
    cells.reset();
    grid.reset();
    file.close_checked("'" + path + "'");
  }
  publish(target, step, render(e));
  return path;
}

GridSnapshotSeries::Entry GridSnapshotSeries::read_entry(int64_t step) const {
  return read_back(step, [&](const h5::Id& file, const std::string& path, double time) {
    Entry e;
    e.step = step;
    e.time = time;
    std::vector<hsize_t> dims;
    std::vector<int64_t> n = h5::read_int64(file, "grid/n", dims, path);
    std::vector<double> o = h5::read_double(file, "grid/origin", dims, path);
    std::vector<double> h = h5::read_double(file, "grid/spacing", dims, path);
    if (n.size() != 3 || o.size() != 3 || h.size() != 3) throw Error("HDF5 file '" + path + "': malformed /grid");
    e.n = {n[0], n[1], n[2]};
    e.origin = {o[0], o[1], o[2]};
    e.spacing = {h[0], h[1], h[2]};
    h5::Id cells(H5Gopen2(file, "cells", H5P_DEFAULT), H5Gclose);
    if (cells.get() < 0) throw Error("HDF5 file '" + path + "': no group '/cells'");
    for (const std::string& name : h5::members(cells, path)) {
      h5::Id set(H5Dopen2(cells, name.c_str(), H5P_DEFAULT), H5Dclose);
      h5::Id space(H5Dget_space(set), H5Sclose);
      (H5Sget_simple_extent_ndims(space) == 4 ? e.vectors : e.scalars).push_back(name);
    }
    return e;
  });
}

std::string GridSnapshotSeries::render(const Entry& e) const {
  const std::string file = snapshot_file_name(prefix_, e.step);
  const std::string cells = std::to_string(e.n[2]) + " " + std::to_string(e.n[1]) + " " + std::to_string(e.n[0]);
  const std::string nodes =
      std::to_string(e.n[2] + 1) + " " + std::to_string(e.n[1] + 1) + " " + std::to_string(e.n[0] + 1);
  auto zyx = [](const Vec3& v) {
    return xdmf::number(v.z) + " " + xdmf::number(v.y) + " " + xdmf::number(v.x);
  };
  const std::string xml3 = "<DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">";
  std::string g = "   <Grid Name=\"step_" + std::to_string(e.step) + "\" GridType=\"Uniform\">\n";
  g += "    <Time Value=\"" + xdmf::number(e.time) + "\"/>\n";
  g += "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" + nodes + "\"/>\n";
  g += "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
  g += "     " + xml3 + zyx(e.origin) + "</DataItem>\n";
  g += "     " + xml3 + zyx(e.spacing) + "</DataItem>\n";
  g += "    </Geometry>\n";
  for (const std::string& s : e.scalars)
    g += xdmf::attribute(s, "Scalar", "Cell", xdmf::hdf_item(cells, "Float", 8, file, "/cells/" + s));
  for (const std::string& v : e.vectors)
    g += xdmf::attribute(v, "Vector", "Cell", xdmf::hdf_item(cells + " 3", "Float", 8, file, "/cells/" + v));
  return g + "   </Grid>\n";
}

}  // namespace cgdem::io
