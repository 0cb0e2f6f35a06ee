// Thin RAII layer over the HDF5 C API used by the io writers (internal to src/io).
//
// Every failing HDF5 call becomes a cgdem::Error naming the file and the object, with the
// innermost line of HDF5's own error stack appended (e.g. "truncated file: eof = ..."), and
// HDF5 prints nothing itself (see Quiet). Files are created with the 1.8 format (readable
// by HDF5 >= 1.8, i.e. any ParaView/h5py) so that attributes larger than 64 KiB (a long
// resolved configuration) are stored densely.
//
// Every dataset is written with two string attributes, "units" (SI: "m", "m/s", "Pa",
// "1" for a dimensionless number or an index) and "description" (one line), and, when a
// compression level 1..9 is given and it holds at least kMinCompressedBytes, chunked
// along its first axis (chunks of at most kChunkBytes) with HDF5's shuffle + deflate.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/h5_options.hpp"

namespace cgdem::io::h5 {

// While one exists, HDF5 does not print its error stack on the calling thread (cgdem
// reports the failure itself, once). It saves the current automatic error handler, sets
// none, and restores the saved one when it goes out of scope, so nothing stays changed for
// other code in the process (a test, a host program). Scoped, not once per process: in a
// thread-safe HDF5 the handler belongs to each thread's error stack, so a process-wide
// "set once" would only silence the thread that did it; a non-thread-safe HDF5 must not be
// called from two threads at once in any case (cgdem writes and reads files from one
// thread; under MPI each rank is its own process). Every entry point of src/io that calls
// HDF5 holds one; they nest.
class Quiet {
 public:
  Quiet();
  ~Quiet();
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
  bool saved_ = false;
};

// Datasets smaller than this are stored contiguous whatever the level (filters cost more
// than they save on a few values); chunks hold at most kChunkBytes along the first axis.
inline constexpr size_t kMinCompressedBytes = 4096;
inline constexpr size_t kChunkBytes = size_t(1) << 20;

// What a dataset holds: its "units" and "description" attributes.
using Meta = FieldInfo;

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
// Opens an existing file read-only; a missing, non-HDF5, truncated or damaged file is a
// cgdem::Error naming `path` (and HDF5's reason).
Id open_file(const std::string& path);

Id create_group(hid_t loc, const std::string& name, const std::string& file);
bool exists(hid_t loc, const std::string& path);

// Datasets of native doubles / int64 / int32, row-major with the given dimensions, with
// their "units" and "description"; `level` 0 (contiguous) or 1..9 (shuffle + deflate).
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const double* data,
           const std::string& file, const Meta& meta, int level);
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int64_t* data,
           const std::string& file, const Meta& meta, int level);
void write(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const int* data,
           const std::string& file, const Meta& meta, int level);
// Error unless 0 <= level <= 9 (and, for level > 0, unless this HDF5 has shuffle and deflate).
void check_level(int level, const std::string& file);

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
