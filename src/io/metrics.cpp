#include "io/metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::io {

void write_metrics(const std::string& path, const Metrics& m) {
  std::string text = "name,value\n";
  for (const auto& [name, value] : m) {
    if (name.empty() || name.find_first_of(", \t\r\n") != std::string::npos)
      throw Error(fmt::format("metrics: invalid metric name '{}'", name));
    text += std::isfinite(value) ? fmt::format("{},{:.17g}\n", name, value) : fmt::format("{},nan\n", name);
  }
  write_file_atomic(path, text);
}

Metrics read_metrics(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read " + path);
  std::string line;
  int n = 0;
  auto next = [&] {  // the next line that is not a '#' comment
    while (std::getline(in, line)) {
      ++n;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty() || line[0] != '#') return true;
    }
    return false;
  };
  if (!next() || line != "name,value") throw Error(path + ": expected the header 'name,value'");
  Metrics m;
  while (next()) {
    if (line.empty()) continue;
    const auto comma = line.find(',');
    if (comma == std::string::npos || comma == 0)
      throw Error(fmt::format("{}:{}: expected 'name,value', got '{}'", path, n, line));
    const std::string value = line.substr(comma + 1);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0') throw Error(fmt::format("{}:{}: '{}' is not a number", path, n, value));
    m.emplace_back(line.substr(0, comma), v);
  }
  return m;
}

double metric(const Metrics& m, const std::string& name, const std::string& source) {
  std::string names;
  for (const auto& [k, v] : m) {
    if (k == name) return v;
    names += (names.empty() ? "" : ", ") + k;
  }
  throw Error(fmt::format("{}: no metric '{}' (it has: {})", source, name, names.empty() ? "none" : names));
}

bool has_metric(const Metrics& m, const std::string& name) {
  return std::any_of(m.begin(), m.end(), [&](const auto& kv) { return kv.first == name; });
}

bool may_be_left_out(const std::string& name) {
  auto ends = [&](const char* s) {
    const std::string e(s);
    return name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0;
  };
  auto starts = [&](const char* s) { return name.rfind(s, 0) == 0; };
  if (starts("p_")) return ends("_peak_Pa") || ends("_peak_time_s") || ends("_mean_Pa");
  if (starts("bubble_") || starts("transfer_rate_")) return ends("_peak_m3") || ends("_peak_time_s") || ends("_peak_kg_s");
  return false;
}

}  // namespace cgdem::io
