// How the HDF5 writers store datasets (no HDF5 include: the case reader uses it too).
#pragma once
#include <map>
#include <string>

namespace cgdem::io {

// Deflate level of the snapshot datasets (output.compression): 0 stores them contiguous and
// uncompressed; 1..9 chunk them and apply HDF5's byte shuffle then deflate at that level.
// The default is chosen by measurement (docs/output_files.md, "Compression").
inline constexpr int kDefaultCompression = 1;
inline constexpr int kMaxCompression = 9;

// What a dataset holds, stored as its "units" (SI; "1" for a dimensionless number or an
// index) and "description" (one line) attributes.
struct FieldInfo {
  std::string units, description;
};
using FieldInfos = std::map<std::string, FieldInfo>;  // by field name

}  // namespace cgdem::io
