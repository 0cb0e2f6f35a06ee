#include "io/h5_util.hpp"

#include <filesystem>

namespace cgdem::io::h5 {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw Error("HDF5 file '" + file + "': " + what);
}

hid_t check(hid_t id, const std::string& file, const std::string& what) {
  if (id < 0) fail(file, what);
  return id;
}

void ok(herr_t rc, const std::string& file, const std::string& what) {
  if (rc < 0) fail(file, what);
}

template <class T>
void write_any(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const T* data,
               hid_t type, const std::string& file) {
  Id space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), file,
                 "cannot create dataspace for '" + name + "'"),
           H5Sclose);
  Id set(check(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), file,
               "cannot create dataset '" + name + "'"),
         H5Dclose);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  if (n > 0) ok(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, "cannot write '" + name + "'");
}

template <class T>
std::vector<T> read_any(hid_t loc, const std::string& name, std::vector<hsize_t>& dims, hid_t type,
                        const std::string& file) {
  if (!exists(loc, name)) fail(file, "missing dataset '" + name + "'");
  Id set(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), file, "cannot open dataset '" + name + "'"), H5Dclose);
  Id space(check(H5Dget_space(set), file, "cannot read the shape of '" + name + "'"), H5Sclose);
  int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail(file, "cannot read the rank of '" + name + "'");
  dims.assign(static_cast<size_t>(rank), 0);
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  std::vector<T> out(n);
  if (n > 0) ok(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), file, "cannot read '" + name + "'");
  return out;
}

template <class T>
void write_scalar_attribute(hid_t loc, const std::string& key, T value, hid_t type, const std::string& file) {
  Id space(check(H5Screate(H5S_SCALAR), file, "cannot create dataspace"), H5Sclose);
  Id a(check(H5Acreate2(loc, key.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), file,
             "cannot create attribute '" + key + "'"),
       H5Aclose);
  ok(H5Awrite(a, type, &value), file, "cannot write attribute '" + key + "'");
}

}  // namespace

Id& Id::operator=(Id&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Id::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = H5I_INVALID_HID;
}

void Id::close_checked(const std::string& what) {
  hid_t id = id_;
  id_ = H5I_INVALID_HID;
  if (id >= 0 && close_ && close_(id) < 0) throw Error("HDF5: closing " + what + " failed");
}

Id create_file(const std::string& path, const std::string& name) {
  Id fapl(check(H5Pcreate(H5P_FILE_ACCESS), name, "cannot create property list"), H5Pclose);
  ok(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18), name, "cannot set format version");
  return Id(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), name, "cannot create file"), H5Fclose);
}

Id open_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("HDF5 file '" + path + "' does not exist");
  if (H5Fis_hdf5(path.c_str()) <= 0) fail(path, "not an HDF5 file");
  return Id(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), path, "cannot open"), H5Fclose);
}

Id create_group(hid_t loc, const std::string& name, const std::string& file) {
  return Id(check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), file,
                  "cannot create group '" + name + "'"),
            H5Gclose);
}

bool exists(hid_t loc, const std::string& path) {
  // H5Lexists needs every intermediate group to exist: test the path one link at a time.
  size_t pos = 0;
  while (true) {
    size_t slash = path.find('/', pos);
    std::string prefix = path.substr(0, slash);
    if (!prefix.empty() && H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    pos = slash + 1;
  }
}

void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const double* data,
           const std::string& file) {
  write_any(loc, name, dims, data, H5T_NATIVE_DOUBLE, file);
}
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int64_t* data,
           const std::string& file) {
  write_any(loc, name, dims, data, H5T_NATIVE_INT64, file);
}
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int* data,
           const std::string& file) {
  write_any(loc, name, dims, data, H5T_NATIVE_INT, file);
}

std::vector<double> read_double(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                const std::string& file) {
  return read_any<double>(loc, name, dims, H5T_NATIVE_DOUBLE, file);
}
std::vector<int64_t> read_int64(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                const std::string& file) {
  return read_any<int64_t>(loc, name, dims, H5T_NATIVE_INT64, file);
}
std::vector<int> read_int(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                          const std::string& file) {
  return read_any<int>(loc, name, dims, H5T_NATIVE_INT, file);
}

void write_attribute(hid_t loc, const std::string& key, const std::string& value, const std::string& file) {
  if (key.empty()) fail(file, "attribute name is empty");
  // Fixed-length, NUL-padded string of exactly the value's length (HDF5 needs >= 1 byte).
  Id type(check(H5Tcopy(H5T_C_S1), file, "cannot create string type"), H5Tclose);
  ok(H5Tset_size(type, value.empty() ? 1 : value.size()), file, "cannot size string type");
  ok(H5Tset_strpad(type, H5T_STR_NULLPAD), file, "cannot set string padding");
  ok(H5Tset_cset(type, H5T_CSET_UTF8), file, "cannot set string character set");
  Id space(check(H5Screate(H5S_SCALAR), file, "cannot create dataspace"), H5Sclose);
  Id a(check(H5Acreate2(loc, key.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), file,
             "cannot create attribute '" + key + "'"),
       H5Aclose);
  const char zero = '\0';
  ok(H5Awrite(a, type, value.empty() ? &zero : value.data()), file, "cannot write attribute '" + key + "'");
}

void write_attribute(hid_t loc, const std::string& key, double value, const std::string& file) {
  write_scalar_attribute(loc, key, value, H5T_NATIVE_DOUBLE, file);
}
void write_attribute(hid_t loc, const std::string& key, int64_t value, const std::string& file) {
  write_scalar_attribute(loc, key, value, H5T_NATIVE_INT64, file);
}

std::map<std::string, std::string> read_string_attributes(hid_t loc, const std::string& file) {
  std::map<std::string, std::string> out;
  H5O_info_t info;
  ok(H5Oget_info2(loc, &info, H5O_INFO_NUM_ATTRS), file, "cannot list attributes");
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    Id a(check(H5Aopen_by_idx(loc, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT), file,
               "cannot open attribute"),
         H5Aclose);
    ssize_t len = H5Aget_name(a, 0, nullptr);
    std::string key(static_cast<size_t>(len > 0 ? len : 0), '\0');
    H5Aget_name(a, key.size() + 1, key.data());
    Id type(check(H5Aget_type(a), file, "cannot read type of attribute '" + key + "'"), H5Tclose);
    if (H5Tget_class(type) != H5T_STRING) continue;
    if (H5Tis_variable_str(type) > 0) {
      // Written by another tool (h5py default): read through a variable-length memory type.
      Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mem, H5T_VARIABLE);
      char* s = nullptr;
      ok(H5Aread(a, mem, &s), file, "cannot read attribute '" + key + "'");
      out[key] = s ? s : "";
      H5free_memory(s);
      continue;
    }
    size_t size = H5Tget_size(type);
    std::string value(size, '\0');
    ok(H5Aread(a, type, value.data()), file, "cannot read attribute '" + key + "'");
    value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
    out[key] = value;
  }
  return out;
}

double read_double_attribute(hid_t loc, const std::string& key, const std::string& file) {
  if (H5Aexists(loc, key.c_str()) <= 0) fail(file, "missing attribute '" + key + "'");
  Id a(check(H5Aopen(loc, key.c_str(), H5P_DEFAULT), file, "cannot open attribute '" + key + "'"), H5Aclose);
  double v = 0;
  ok(H5Aread(a, H5T_NATIVE_DOUBLE, &v), file, "attribute '" + key + "' is not a number");
  return v;
}

std::vector<std::string> members(hid_t group, const std::string& file) {
  H5G_info_t info;
  ok(H5Gget_info(group, &info), file, "cannot list group");
  std::vector<std::string> out;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t len = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) fail(file, "cannot read a member name");
    std::string name(static_cast<size_t>(len), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size() + 1, H5P_DEFAULT);
    out.push_back(name);
  }
  return out;
}

}  // namespace cgdem::io::h5
