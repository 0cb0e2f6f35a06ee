#include "scaling/csv_table.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace cgdem::scaling {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double to_number(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str()) return std::numeric_limits<double>::quiet_NaN();
  return v;
}

}  // namespace

bool CsvTable::has(const std::string& name) const {
  for (const auto& n : names)
    if (n == name) return true;
  return false;
}

const std::vector<double>& CsvTable::col(const std::string& name) const {
  for (size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return columns[c];
  throw Error(fmt::format("{}: no column '{}' (it has: {})", source, name, fmt::join(names, ", ")));
}

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("cannot read {}", path));
  CsvTable t;
  t.source = path;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool complete = !text.empty() && text.back() == '\n';
  std::istringstream lines(text);
  std::vector<std::string> all;
  for (std::string l; std::getline(lines, l);) all.push_back(l);
  if (!complete && !all.empty()) all.pop_back();  // a row still being written
  size_t row = 0;
  for (size_t k = 0; k < all.size(); ++k) {
    std::string l = all[k];
    if (!l.empty() && l.back() == '\r') l.pop_back();
    if (l.empty() || l[0] == '#') continue;
    auto f = split(l);
    if (t.names.empty()) {
      t.names = f;
      t.columns.assign(f.size(), {});
      continue;
    }
    if (f.size() != t.names.size())
      throw Error(fmt::format("{} line {}: {} fields, the header has {}", path, k + 1, f.size(), t.names.size()));
    for (size_t c = 0; c < f.size(); ++c) t.columns[c].push_back(to_number(f[c]));
    ++row;
  }
  if (t.names.empty()) throw Error(fmt::format("{}: no header line", path));
  return t;
}

}  // namespace cgdem::scaling
