#include "io/xdmf_series.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::io {

void XdmfTimeSeries::set(int64_t step, std::string grid_xml) {
  grids_.erase(grids_.upper_bound(step), grids_.end());
  grids_[step] = std::move(grid_xml);
}

std::vector<int64_t> XdmfTimeSeries::steps() const {
  std::vector<int64_t> out;
  for (const auto& kv : grids_) out.push_back(kv.first);
  return out;
}

std::string XdmfTimeSeries::text() const {
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"3.0\">\n"
      " <Domain>\n"
      "  <Grid Name=\"" + xdmf::escape(name_) + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& kv : grids_) out += kv.second;
  out +=
      "  </Grid>\n"
      " </Domain>\n"
      "</Xdmf>\n";
  return out;
}

void XdmfTimeSeries::write() const { write_file_atomic(path_, text()); }

namespace xdmf {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string hdf_item(const std::string& dims, const char* number_type, int precision, const std::string& file,
                     const std::string& dataset) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + number_type + "\" Precision=\"" +
         std::to_string(precision) + "\" Format=\"HDF\">" + escape(file + ":" + dataset) + "</DataItem>";
}

std::string attribute(const std::string& name, const char* type, const char* center, const std::string& item) {
  return "    <Attribute Name=\"" + escape(name) + "\" AttributeType=\"" + type + "\" Center=\"" + center +
         "\">\n     " + item + "\n    </Attribute>\n";
}

}  // namespace xdmf

std::string snapshot_file_name(const std::string& prefix, int64_t step) {
  if (step < 0) throw Error("snapshot step must be >= 0, got " + std::to_string(step));
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06lld.h5", static_cast<long long>(step));
  return prefix + buf;
}

std::vector<int64_t> find_snapshot_steps(const std::string& dir, const std::string& prefix) {
  std::vector<int64_t> steps;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    const std::string head = prefix + "_", tail = ".h5";
    if (f.size() < head.size() + 6 + tail.size() || f.compare(0, head.size(), head) != 0 ||
        f.compare(f.size() - tail.size(), tail.size(), tail) != 0)
      continue;
    const std::string digits = f.substr(head.size(), f.size() - head.size() - tail.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    steps.push_back(std::stoll(digits));
  }
  std::sort(steps.begin(), steps.end());
  return steps;
}

void check_series_name(const std::string& name, const char* what) {
  if (name.empty()) throw Error(std::string(what) + " is empty");
  for (char c : name)
    if (c == '/' || c == '\\' || c == ':' || static_cast<unsigned char>(c) < 32)
      throw Error(std::string(what) + " '" + name + "' may not contain '/', '\\', ':' or control characters");
}

}  // namespace cgdem::io
