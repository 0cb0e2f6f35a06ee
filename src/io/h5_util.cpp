#include "io/h5_util.hpp"

#include <algorithm>
#include <filesystem>

namespace cgdem::io::h5 {
namespace {

// The innermost description on HDF5's error stack of this thread (the most specific
// reason: "truncated file: eof = ...", "wrong B-tree signature"), then the stack is cleared.
std::string hdf5_reason() {
  std::vector<std::string> lines;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
        if (e && e->desc && *e->desc) static_cast<std::vector<std::string>*>(out)->push_back(e->desc);
        return 0;
      },
      &lines);
  H5Eclear2(H5E_DEFAULT);
  return lines.empty() ? std::string() : lines.back();
}

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw Error("HDF5 file '" + file + "': " + what);
}

// A failed HDF5 call: our words, then HDF5's reason in parentheses.
[[noreturn]] void fail_call(const std::string& file, const std::string& what) {
  const std::string why = hdf5_reason();
  fail(file, why.empty() ? what : what + " (HDF5: " + why + ")");
}

hid_t check(hid_t id, const std::string& file, const std::string& what) {
  if (id < 0) fail_call(file, what);
  return id;
}

void ok(herr_t rc, const std::string& file, const std::string& what) {
  if (rc < 0) fail_call(file, what);
}

// Dataset creation properties: contiguous, or chunks of whole rows along the first axis
// (at most kChunkBytes, at least one row) with shuffle + deflate at `level`.
Id creation_properties(const std::vector<hsize_t>& dims, size_t value_bytes, int level, const std::string& name,
                       const std::string& file) {
  Id dcpl(check(H5Pcreate(H5P_DATASET_CREATE), file, "cannot create property list"), H5Pclose);
  size_t total = value_bytes;
  for (hsize_t d : dims) total *= static_cast<size_t>(d);
  if (level <= 0 || dims.empty() || total < kMinCompressedBytes) return dcpl;
  const size_t row = total / static_cast<size_t>(dims[0]);
  std::vector<hsize_t> chunk = dims;
  chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], kChunkBytes / std::max<size_t>(row, 1)));
  ok(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), file, "cannot chunk '" + name + "'");
  ok(H5Pset_shuffle(dcpl), file, "cannot set the shuffle filter on '" + name + "'");
  ok(H5Pset_deflate(dcpl, static_cast<unsigned>(level)), file, "cannot set deflate on '" + name + "'");
  return dcpl;
}

template <class T>
void write_any(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const T* data,
               hid_t type, const std::string& file, const Meta& meta, int level) {
  if (meta.units.empty() || meta.description.empty())
    fail(file, "dataset '" + name + "' needs a unit and a description");
  check_level(level, file);
  Id space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), file,
                 "cannot create dataspace for '" + name + "'"),
           H5Sclose);
  Id dcpl = creation_properties(dims, sizeof(T), level, name, file);
  Id set(check(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), file,
               "cannot create dataset '" + name + "'"),
         H5Dclose);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  if (n > 0) ok(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, "cannot write '" + name + "'");
  write_attribute(set, "units", meta.units, file);
  write_attribute(set, "description", meta.description, file);
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

Quiet::Quiet() {
  saved_ = H5Eget_auto2(H5E_DEFAULT, &func_, &data_) >= 0;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Quiet::~Quiet() {
  if (saved_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
}

void check_level(int level, const std::string& file) {
  if (level < 0 || level > 9) fail(file, "compression level must be 0..9, got " + std::to_string(level));
  if (level == 0) return;
  static const bool have = H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 && H5Zfilter_avail(H5Z_FILTER_SHUFFLE) > 0;
  if (!have) fail(file, "this HDF5 library has no deflate/shuffle filter: set output.compression = 0");
}

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
  if (id >= 0 && close_ && close_(id) < 0) {
    const std::string why = hdf5_reason();
    throw Error("HDF5: closing " + what + " failed" + (why.empty() ? "" : " (HDF5: " + why + ")"));
  }
}

Id create_file(const std::string& path, const std::string& name) {
  Quiet quiet;
  Id fapl(check(H5Pcreate(H5P_FILE_ACCESS), name, "cannot create property list"), H5Pclose);
  ok(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18), name, "cannot set format version");
  return Id(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), name, "cannot create file"), H5Fclose);
}

Id open_file(const std::string& path) {
  Quiet quiet;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("HDF5 file '" + path + "' does not exist");
  const htri_t is_h5 = H5Fis_hdf5(path.c_str());
  if (is_h5 == 0) fail(path, "not an HDF5 file (no HDF5 signature)");
  if (is_h5 < 0) fail_call(path, "cannot be read as HDF5");
  return Id(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), path,
                  "cannot open (truncated or damaged?)"),
            H5Fclose);
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
           const std::string& file, const Meta& meta, int level) {
  write_any(loc, name, dims, data, H5T_NATIVE_DOUBLE, file, meta, level);
}
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int64_t* data,
           const std::string& file, const Meta& meta, int level) {
  write_any(loc, name, dims, data, H5T_NATIVE_INT64, file, meta, level);
}
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int* data,
           const std::string& file, const Meta& meta, int level) {
  write_any(loc, name, dims, data, H5T_NATIVE_INT, file, meta, level);
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
