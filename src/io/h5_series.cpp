#include "io/h5_series.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "io/h5_util.hpp"

namespace cgdem::io {

H5Series::H5Series(std::string dir, std::string prefix, Attributes attributes, int compression, const char* what)
    : dir_(std::move(dir)),
      prefix_(std::move(prefix)),
      attributes_(std::move(attributes)),
      compression_(compression),
      index_(dir_ + "/" + prefix_ + ".xdmf", prefix_) {
  check_series_name(prefix_, (std::string(what) + " prefix").c_str());
  detail::check_reserved_attributes(attributes_, what);
  h5::check_level(compression_, dir_ + "/" + prefix_ + "_*.h5");
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (!std::filesystem::is_directory(dir_)) throw Error("cannot create output directory '" + dir_ + "'");
}

void H5Series::publish(AtomicTarget& target, int64_t step, std::string grid_xml) {
  target.commit();
  index_.set(step, std::move(grid_xml));
  index_.write();
}

std::string H5Series::snapshot_path(int64_t step) const { return dir_ + "/" + snapshot_file_name(prefix_, step); }

}  // namespace cgdem::io
