// Thin RAII layer over the HDF5 C API used by the io writers (internal to src/io).
//
// Every failing HDF5 call becomes a cgdem::Error naming the file and the object. Files are
// created with the 1.8 format (readable by HDF5 >= 1.8, i.e. any ParaView/h5py) so that
// attributes larger than 64 KiB (a long resolved configuration) are stored densely.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace cgdem::io::h5 {

// Owns one hid_t and closes it with the matching H5?close.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer close) : id_(id), close_(close) {}
  Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Id& operator=(Id&& o) noexcept;
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { reset(); }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  void reset();
  // Closes now and reports a failure (used for files: close errors mean lost data).
  void close_checked(const std::string& what);

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

// Creates (truncates) `path` for writing; `name` is the user-visible file name for errors.
Id create_file(const std::string& path, const std::string& name);
// Opens an existing file read-only; a missing or non-HDF5 file is a cgdem::Error.
Id open_file(const std::string& path);

Id create_group(hid_t loc, const std::string& name, const std::string& file);
bool exists(hid_t loc, const std::string& path);

// Datasets of native doubles / int64 / int32, row-major with the given dimensions.
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const double* data,
           const std::string& file);
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int64_t* data,
           const std::string& file);
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int* data,
           const std::string& file);

// Reads a whole dataset converted to the requested type; `dims` receives its shape.
std::vector<double> read_double(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                const std::string& file);
std::vector<int64_t> read_int64(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                const std::string& file);
std::vector<int> read_int(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                          const std::string& file);

// Attributes on an object: fixed-length strings and numeric scalars.
void write_attribute(hid_t loc, const std::string& key, const std::string& value, const std::string& file);
void write_attribute(hid_t loc, const std::string& key, double value, const std::string& file);
void write_attribute(hid_t loc, const std::string& key, int64_t value, const std::string& file);
// All string-valued attributes of `loc` (numeric ones are skipped).
std::map<std::string, std::string> read_string_attributes(hid_t loc, const std::string& file);
double read_double_attribute(hid_t loc, const std::string& key, const std::string& file);

// Names of the direct members of a group, in name order.
std::vector<std::string> members(hid_t group, const std::string& file);

}  // namespace cgdem::io::h5
