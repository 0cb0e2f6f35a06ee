#include "io/metrics.hpp"

#include <fmt/format.h>

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
  if (!std::getline(in, line) || line != "name,value") throw Error(path + ": expected the header 'name,value'");
  Metrics m;
  for (int n = 2; std::getline(in, line); ++n) {
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

}  // namespace cgdem::io
