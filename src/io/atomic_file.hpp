// Atomic output files: an interrupted run never leaves a half-written result.
//
// Protocol (POSIX): the bytes go to a temporary `<path>.tmp-<pid>` in the SAME directory
// (so that rename() stays within one file system), the temporary is fsync'ed, then
// renamed over `<path>` (rename is atomic: readers see the old or the new file, never a
// mix), and finally the directory is fsync'ed so that the rename itself is durable.
//
// Two entry points:
//   * write_file_atomic(path, bytes) for text we build in memory (CSV, XDMF);
//   * AtomicTarget for libraries that open and write the file themselves (HDF5):
//       AtomicTarget t(path);  H5Fcreate(t.tmp_path().c_str(), ...); ... H5Fclose;  t.commit();
//     If commit() is never reached (exception, early return) the destructor removes the
//     temporary and the previous `<path>` is untouched.
#pragma once
#include <string>
#include <string_view>

namespace cgdem::io {

// The temporary name used for `path`: `<path>.tmp-<pid>`.
std::string temporary_path(const std::string& path);

// fsync(tmp); rename(tmp, path); fsync(directory of path). Throws cgdem::Error on failure
// (the temporary is removed in that case).
void commit_temporary(const std::string& tmp, const std::string& path);

// Writes `bytes` to `path` atomically (temporary + fsync + rename). Throws cgdem::Error.
void write_file_atomic(const std::string& path, std::string_view bytes);

// Scoped temporary for writers that create the file themselves.
class AtomicTarget {
 public:
  explicit AtomicTarget(std::string path);
  ~AtomicTarget();  // removes the temporary unless committed
  AtomicTarget(const AtomicTarget&) = delete;
  AtomicTarget& operator=(const AtomicTarget&) = delete;

  const std::string& path() const { return path_; }
  const std::string& tmp_path() const { return tmp_; }
  // Precondition: the writer has closed the temporary. Postcondition: `path` holds it.
  void commit();

 private:
  std::string path_, tmp_;
  bool committed_ = false;
};

}  // namespace cgdem::io
