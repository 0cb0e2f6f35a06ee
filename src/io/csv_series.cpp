#include "io/csv_series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::io {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t c; (c = line.find(',', start)) != std::string::npos; start = c + 1) out.push_back(line.substr(start, c - start));
  out.push_back(line.substr(start));
  return out;
}

std::string column_line(const CsvColumns& cols) {
  std::string s;
  for (size_t i = 0; i < cols.size(); ++i) {
    if (i) s += ',';
    s += cols[i].name;
  }
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read {}", path));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    out.push_back(l);
  }
  if (!text.empty() && text.back() != '\n' && !out.empty()) out.pop_back();  // a line still being written
  return out;
}

}  // namespace

std::string unit_suffix(const std::string& unit) {
  if (unit == "1") return "";
  std::string s;
  for (char ch : unit) {
    if (ch == '^') continue;
    s += (ch == '/' || ch == ' ') ? '_' : ch;
  }
  return s;
}

std::string quantity_name(const std::string& name, const std::string& unit) {
  const std::string suffix = unit.empty() ? "" : unit_suffix(unit);
  if (suffix.empty() || !ends_with(name, fmt::format("_{}", suffix)) || name.size() == suffix.size() + 1) return name;
  return name.substr(0, name.size() - suffix.size() - 1);
}

void check_columns(const CsvColumns& columns, const std::string& what) {
  if (columns.empty()) throw Error(fmt::format("{}: no columns", what));
  for (size_t i = 0; i < columns.size(); ++i) {
    const CsvColumn& c = columns[i];
    if (c.name.empty() || c.name.find_first_of(",#\"' \t\r\n") != std::string::npos)
      throw Error(fmt::format("{}: bad column name '{}'", what, c.name));
    for (size_t j = 0; j < i; ++j)
      if (columns[j].name == c.name) throw Error(fmt::format("{}: column '{}' appears twice", what, c.name));
    if (c.unit.empty() || c.unit.find_first_of(",\r\n") != std::string::npos)
      throw Error(fmt::format("{}: column '{}': bad unit '{}'", what, c.name, c.unit));
    if (c.description.empty() || c.description.find_first_of("\r\n") != std::string::npos)
      throw Error(fmt::format("{}: column '{}': the description must be one non-empty line", what, c.name));
    const std::string suffix = unit_suffix(c.unit);
    if (!suffix.empty() && (!ends_with(c.name, fmt::format("_{}", suffix)) || c.name.size() == suffix.size() + 1))
      throw Error(fmt::format("{}: column '{}' in {} must end with '_{}'", what, c.name, c.unit, suffix));
  }
}

std::string csv_preamble(const CsvColumns& columns, const std::vector<std::string>& provenance,
                         const std::string& what) {
  check_columns(columns, what);
  std::string s = column_line(columns) + "\n";
  for (const std::string& p : provenance) {
    std::istringstream lines(p);
    for (std::string l; std::getline(lines, l);) s += fmt::format("# {}\n", l);
  }
  for (const CsvColumn& c : columns) s += fmt::format("# {}: {}, {}\n", c.name, c.unit, c.description);
  return s;
}

CsvSeries::CsvSeries(std::string path, CsvColumns columns, const std::vector<std::string>& provenance,
                     std::optional<double> continue_after)
    : path_(std::move(path)), columns_(std::move(columns)) {
  std::string text = csv_preamble(columns_, provenance, path_);
  std::error_code ec;
  if (continue_after && std::filesystem::exists(path_, ec)) {
    // Keep the column line, every '#' line and the rows up to the restart time.
    const std::string want = column_line(columns_);
    std::string kept, first;
    for (const std::string& l : lines_of(read_all(path_))) {
      if (l.empty()) continue;
      if (first.empty() && l[0] != '#') {
        first = l;
        if (first != want)
          throw Error(fmt::format("{}: cannot continue it, its columns are '{}' but this run writes '{}' (start "
                                  "the run in a fresh --output folder)",
                                  path_, first, want));
        kept += l + "\n";
        continue;
      }
      if (l[0] == '#') {
        kept += l + "\n";
        continue;
      }
      char* end = nullptr;
      const double t = std::strtod(l.c_str(), &end);
      if (end == l.c_str() || (*end != ',' && *end != '\0')) break;
      if (t > *continue_after + 1e-12) break;
      kept += l + "\n";
    }
    if (first.empty()) throw Error(fmt::format("{}: cannot continue it, the file has no column line", path_));
    text = kept;
  }
  write_file_atomic(path_, text);
  file_ = std::fopen(path_.c_str(), "a");
  if (!file_) throw Error(fmt::format("cannot append to {}: {}", path_, std::strerror(errno)));
}

CsvSeries::~CsvSeries() {
  if (file_) std::fclose(file_);
}

void CsvSeries::write_text(const std::string& text) {
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw Error(fmt::format("write to {} failed: {}", path_, std::strerror(errno)));
}

void CsvSeries::row(const std::string& fields) {
  const size_t n = 1 + static_cast<size_t>(std::count(fields.begin(), fields.end(), ','));
  if (n != columns_.size() || fields.find('\n') != std::string::npos)
    throw Error(fmt::format("{}: a row of {} fields for {} columns", path_, n, columns_.size()));
  write_text(fields + "\n");
}

void CsvSeries::rows(const std::string& lines) {
  for (size_t start = 0; start < lines.size();) {
    const size_t nl = lines.find('\n', start);
    if (nl == std::string::npos) throw Error(fmt::format("{}: rows must end with a newline", path_));
    row(lines.substr(start, nl - start));
    start = nl + 1;
  }
}

void CsvSeries::numbers(const std::vector<double>& values) {
  std::string line;
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';
    line += fmt::format("{:.10g}", values[i]);
  }
  row(line);
}

void CsvSeries::flush() {
  if (std::fflush(file_) != 0) throw Error(fmt::format("flush of {} failed: {}", path_, std::strerror(errno)));
}

void write_csv_file(const std::string& path, const CsvColumns& columns, const std::vector<std::string>& provenance,
                    const std::string& rows) {
  write_file_atomic(path, csv_preamble(columns, provenance, path) + rows);
}

std::string legacy_column_unit(const std::string& n) {
  static const std::map<std::string, std::string> units = {
      {"t", "s"},
      {"E_kin_trans", "J"},
      {"E_kin_rot", "J"},
      {"E_kin_rot_orig", "J"},
      {"E_pot", "J"},
      {"E_elastic", "J"},
      {"E_diss_damping", "J"},
      {"E_diss_friction", "J"},
      {"W_walls", "J"},
      {"W_air", "J"},
      {"E_balance", "J"},
      {"px", "kg m/s"},
      {"py", "kg m/s"},
      {"pz", "kg m/s"},
      {"mass", "kg"},
      {"particles", "1"},
      {"removed", "1"},
      {"inside_walls", "1"},
      {"mass_in_die", "kg"},
      {"transfer_rate", "kg/s"},
      {"impacts", "1"},
      {"mass_in_shoe", "kg"},
      {"Q_cavity", "m^3/s"},
      {"Q_shoe_walls", "m^3/s"},
      {"Q_open_mouth", "m^3/s"},
      {"bubbles", "1"},
      {"V_bubbles", "m^3"},
      {"V_bubble_max", "m^3"},
      {"z_bubble", "m"},
      {"z_bubble_top", "m"},
      {"V_bubbles_shoe", "m^3"},
      {"V_sealed", "m^3"},
      {"id", "1"},
      {"speed_down", "m/s"},
      {"bin", "1"},
      {"parcels", "1"}};
  if (const auto it = units.find(n); it != units.end()) return it->second;
  if (n.size() > 2 && n.rfind("p_", 0) == 0) return "Pa";  // a pressure cell
  return "";
}

bool CsvTable::has(const std::string& name) const { return index(name) >= 0; }

long CsvTable::index(const std::string& name) const {
  for (size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return static_cast<long>(c);
  for (size_t c = 0; c < names.size(); ++c)
    if (quantity(c) == name) return static_cast<long>(c);
  return -1;
}

const std::vector<double>& CsvTable::col(const std::string& name) const {
  const long c = index(name);
  if (c < 0) throw Error(fmt::format("{}: no column '{}' (it has: {})", source, name, fmt::join(names, ", ")));
  return columns[static_cast<size_t>(c)];
}

std::string CsvTable::revision() const {
  for (const std::string& c : comments) {
    if (c.rfind("cgdem ", 0) != 0) continue;
    std::string rev = c.substr(6);
    rev = rev.substr(0, rev.find_first_of(" ,"));
    if (!rev.empty()) return rev;
  }
  return "";
}

CsvTable read_csv_table(const std::string& path) {
  CsvTable t;
  t.source = path;
  const std::vector<std::string> lines = lines_of(read_all(path));
  std::map<std::string, std::pair<std::string, std::string>> described;  // name -> (unit, description)
  for (size_t k = 0; k < lines.size(); ++k) {
    const std::string& l = lines[k];
    if (l.empty()) continue;
    if (l[0] == '#') {
      std::string c = l.substr(1);
      if (!c.empty() && c[0] == ' ') c.erase(0, 1);
      t.comments.push_back(c);
      // "<name>: <unit>, <description>" for a column of the column line
      const size_t colon = c.find(": "), comma = c.find(", ", colon == std::string::npos ? 0 : colon);
      if (!t.names.empty() && colon != std::string::npos && comma != std::string::npos) {
        const std::string name = c.substr(0, colon);
        if (std::find(t.names.begin(), t.names.end(), name) != t.names.end())
          described[name] = {c.substr(colon + 2, comma - colon - 2), c.substr(comma + 2)};
      }
      continue;
    }
    const std::vector<std::string> f = split(l);
    if (t.names.empty()) {
      t.names = f;
      t.columns.assign(f.size(), {});
      continue;
    }
    if (f.size() != t.names.size())
      throw Error(fmt::format("{} line {}: {} fields, the column line has {}", path, k + 1, f.size(), t.names.size()));
    for (size_t c = 0; c < f.size(); ++c) {
      char* end = nullptr;
      const double v = std::strtod(f[c].c_str(), &end);
      t.columns[c].push_back(end == f[c].c_str() ? std::numeric_limits<double>::quiet_NaN() : v);
    }
  }
  if (t.names.empty()) throw Error(fmt::format("{}: no column line", path));
  t.self_describing = described.size() == t.names.size();
  for (std::string& n : t.names) {
    if (const auto it = described.find(n); it != described.end()) {
      t.units.push_back(it->second.first);
      t.descriptions.push_back(it->second.second);
      continue;
    }
    t.descriptions.emplace_back();
    const std::string unit = t.self_describing || !described.empty() ? "" : legacy_column_unit(n);
    t.units.push_back(unit);
    if (!unit.empty() && unit != "1") n += fmt::format("_{}", unit_suffix(unit));  // the old layout: bare names
  }
  return t;
}

}  // namespace cgdem::io
