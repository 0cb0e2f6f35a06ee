#include "io/snapshot_series.hpp"

#include "io/atomic_file.hpp"
#include "io/h5_util.hpp"
#include "io/particle_h5.hpp"

namespace cgdem::io {
namespace {

const char* const kReserved[] = {"velocity", "omega", "position", "diameter", "id", "species"};

}  // namespace

SnapshotSeries::SnapshotSeries(std::string dir, std::string prefix, Attributes attributes, bool resume,
                               int compression)
    : H5Series(std::move(dir), std::move(prefix), std::move(attributes), compression, "snapshot") {
  if (resume)
    for (int64_t s : existing_steps()) index_.set(s, render(read_entry(s)));
}

std::string SnapshotSeries::write(int64_t step, double time, const ParticleTable& table, const ScalarFields& extra,
                                  const FieldInfos& info) {
  h5::Quiet quiet;
  const std::string path = snapshot_path(step);
  table.validate(path);
  Entry e{step, time, table.size(), table.has_velocity(), table.has_omega(), {}};
  for (const auto& [name, values] : extra) {
    check_series_name(name, "snapshot field name");
    for (const char* r : kReserved)
      if (name == r) throw Error("snapshot field name '" + name + "' is reserved");
    if (values.size() != table.size())
      throw Error(path + ": field '" + name + "' has " + std::to_string(values.size()) + " values for " +
                  std::to_string(table.size()) + " particles");
    if (!info.count(name)) throw Error(path + ": field '" + name + "' has no units and description");
    e.fields.push_back(name);
  }
  AtomicTarget target(path);
  {
    h5::Id file = h5::create_file(target.tmp_path(), path);
    detail::write_file_attributes(file, attributes_, "cgdem particle snapshot: one row per parcel, SI units",
                                  Instant{time, step}, path);
    detail::write_particle_group(file, table, path, compression_);
    h5::Id g = h5::create_group(file, "fields", path);
    for (const auto& [name, values] : extra)
      h5::write(g, name, {values.size()}, values.data(), path, info.at(name), compression_);
    g.reset();
    file.close_checked("'" + path + "'");
  }
  publish(target, step, render(e));
  return path;
}

SnapshotSeries::Entry SnapshotSeries::read_entry(int64_t step) const {
  return read_back(step, [&](const h5::Id& file, const std::string& path, double time) {
    Entry e;
    e.step = step;
    e.time = time;
    std::vector<hsize_t> dims;
    e.n = h5::read_double(file, "particles/d", dims, path).size();
    e.has_v = h5::exists(file, "particles/v");
    e.has_omega = h5::exists(file, "particles/omega");
    e.has_vertex = h5::exists(file, "particles/vertex");
    if (h5::exists(file, "fields")) {
      h5::Id g(H5Gopen2(file, "fields", H5P_DEFAULT), H5Gclose);
      e.fields = h5::members(g, path);
    }
    return e;
  });
}

std::string SnapshotSeries::render(const Entry& e) const {
  const std::string file = snapshot_file_name(prefix_, e.step);  // relative to the index
  const std::string n = std::to_string(e.n), n3 = n + " 3";
  std::string g = "   <Grid Name=\"step_" + std::to_string(e.step) + "\" GridType=\"Uniform\">\n";
  g += "    <Time Value=\"" + xdmf::number(e.time) + "\"/>\n";
  // The connectivity makes every reader build one vertex cell per parcel (without it the
  // Xdmf3 readers of ParaView make none, and meshio needs a DataItem here).
  g += "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n + "\" NodesPerElement=\"1\"";
  if (e.has_vertex)
    g += ">\n     " + xdmf::hdf_item(n + " 1", "Int", 8, file, "/particles/vertex") + "\n    </Topology>\n";
  else
    g += "/>\n";
  g += "    <Geometry GeometryType=\"XYZ\">\n     " + xdmf::hdf_item(n3, "Float", 8, file, "/particles/x") +
       "\n    </Geometry>\n";
  if (e.has_v)
    g += xdmf::attribute("velocity", "Vector", "Node", xdmf::hdf_item(n3, "Float", 8, file, "/particles/v"));
  if (e.has_omega)
    g += xdmf::attribute("omega", "Vector", "Node", xdmf::hdf_item(n3, "Float", 8, file, "/particles/omega"));
  g += xdmf::attribute("position", "Vector", "Node", xdmf::hdf_item(n3, "Float", 8, file, "/particles/x"));
  g += xdmf::attribute("diameter", "Scalar", "Node", xdmf::hdf_item(n, "Float", 8, file, "/particles/d"));
  g += xdmf::attribute("id", "Scalar", "Node", xdmf::hdf_item(n, "Int", 8, file, "/particles/id"));
  g += xdmf::attribute("species", "Scalar", "Node", xdmf::hdf_item(n, "Int", 4, file, "/particles/species"));
  for (const std::string& f : e.fields)
    g += xdmf::attribute(f, "Scalar", "Node", xdmf::hdf_item(n, "Float", 8, file, "/fields/" + f));
  return g + "   </Grid>\n";
}

}  // namespace cgdem::io
