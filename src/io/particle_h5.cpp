#include "io/particle_h5.hpp"

#include <numeric>

#include "core/revision.hpp"
#include "io/atomic_file.hpp"
#include "io/h5_util.hpp"

namespace cgdem::io {
namespace detail {

void check_reserved_attributes(const Attributes& attributes, const char* what) {
  for (const char* k : {"description", "time", "time_units", "step"})
    if (attributes.count(k)) throw Error(std::string(what) + " attribute '" + k + "' is reserved");
}

void write_file_attributes(hid_t file, const Attributes& attributes, const std::string& description,
                           std::optional<Instant> at, const std::string& name) {
  check_reserved_attributes(attributes, "HDF5 file");
  for (const auto& [k, v] : attributes) h5::write_attribute(file, k, v, name);
  if (!attributes.count("cgdem_revision")) h5::write_attribute(file, "cgdem_revision", kGitRevision, name);
  h5::write_attribute(file, "description", description, name);
  if (at) {
    h5::write_attribute(file, "time", at->time, name);
    h5::write_attribute(file, "time_units", "s", name);
    h5::write_attribute(file, "step", at->step, name);
  }
}

void write_particle_group(hid_t file, const ParticleTable& t, const std::string& name, int level) {
  t.validate(name);
  const hsize_t n = t.size();
  h5::Id g = h5::create_group(file, "particles", name);
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
  h5::write(g, "id", {n}, t.id.data(), name, {"1", "parcel id (stable over the run; not the row number)"}, level);
  h5::write(g, "species", {n}, t.species.data(), name,
            {"1", "species index: 0 is the first [[particles.species]] of the case"}, level);
  h5::write(g, "x", {n, 3}, reinterpret_cast<const double*>(t.x.data()), name,
            {"m", "parcel centre position (x, y, z)"}, level);
  if (t.has_velocity())
    h5::write(g, "v", {n, 3}, reinterpret_cast<const double*>(t.v.data()), name,
              {"m/s", "parcel velocity (x, y, z)"}, level);
  if (t.has_omega())
    h5::write(g, "omega", {n, 3}, reinterpret_cast<const double*>(t.omega.data()), name,
              {"rad/s", "parcel angular velocity (x, y, z)"}, level);
  h5::write(g, "d", {n}, t.d.data(), name, {"m", "parcel diameter as simulated (l times the original diameter)"},
            level);
  std::vector<int64_t> vertex(n);
  std::iota(vertex.begin(), vertex.end(), int64_t{0});
  h5::write(g, "vertex", {n, 1}, vertex.data(), name,
            {"1", "row numbers 0..N-1: the connectivity of the XDMF Polyvertex topology (one vertex per parcel)"},
            level);
}

namespace {

std::string shape(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(dims[i]);
  }
  return s + "]";
}

std::vector<Vec3> read_vec3(hid_t g, const std::string& ds, const std::string& name) {
  std::vector<hsize_t> dims;
  std::vector<double> flat = h5::read_double(g, ds, dims, name);
  if (dims.size() != 2 || dims[1] != 3)
    throw Error("HDF5 file '" + name + "': '/particles/" + ds + "' has shape " + shape(dims) + ", expected [N,3]");
  std::vector<Vec3> out(dims[0]);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return out;
}

void expect_1d(const std::vector<hsize_t>& dims, const std::string& ds, const std::string& name) {
  if (dims.size() != 1)
    throw Error("HDF5 file '" + name + "': '/particles/" + ds + "' has shape " + shape(dims) + ", expected [N]");
}

}  // namespace

ParticleTable read_particle_group(hid_t file, const std::string& name) {
  h5::Quiet quiet;
  if (!h5::exists(file, "particles")) throw Error("HDF5 file '" + name + "': no group '/particles'");
  h5::Id g(H5Gopen2(file, "particles", H5P_DEFAULT), H5Gclose);
  if (g.get() < 0) throw Error("HDF5 file '" + name + "': cannot open '/particles'");
  ParticleTable t;
  std::vector<hsize_t> dims;
  t.id = h5::read_int64(g, "id", dims, name);
  expect_1d(dims, "id", name);
  t.species = h5::read_int(g, "species", dims, name);
  expect_1d(dims, "species", name);
  t.d = h5::read_double(g, "d", dims, name);
  expect_1d(dims, "d", name);
  t.x = read_vec3(g, "x", name);
  if (h5::exists(g, "v")) t.v = read_vec3(g, "v", name);
  if (h5::exists(g, "omega")) t.omega = read_vec3(g, "omega", name);
  t.validate("HDF5 file '" + name + "'");
  return t;
}

}  // namespace detail

void write_particles_h5(const std::string& path, const ParticleTable& table, const Attributes& attributes,
                        int compression, std::optional<Instant> at) {
  table.validate(path);
  h5::check_level(compression, path);
  detail::check_reserved_attributes(attributes, "HDF5 file");
  h5::Quiet quiet;
  AtomicTarget target(path);
  {
    h5::Id file = h5::create_file(target.tmp_path(), path);
    detail::write_file_attributes(file, attributes, "cgdem particle state: one row per parcel, SI units", at, path);
    detail::write_particle_group(file, table, path, compression);
    file.close_checked("'" + path + "'");
  }
  target.commit();
}

ParticleTable read_particles_h5(const std::string& path, Attributes* attributes) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  if (attributes) *attributes = h5::read_string_attributes(file, path);
  return detail::read_particle_group(file, path);
}

Attributes read_h5_attributes(const std::string& path) {
  h5::Quiet quiet;
  h5::Id file = h5::open_file(path);
  return h5::read_string_attributes(file, path);
}

}  // namespace cgdem::io
