#include "app/run_metrics.hpp"

#include <fmt/format.h>

#include <cmath>
#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace cgdem::app {

namespace {

// Columns of a CSV written by run_case ('#' comment lines skipped), by name.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  const std::vector<double>& col(const std::string& n, const std::string& file) const {
    for (size_t c = 0; c < names.size(); ++c)
      if (names[c] == n) return cols[c];
    throw Error(fmt::format("{}: no column '{}'", file, n));
  }
};

Table read_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read " + path);
  Table t;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cells;
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (t.names.empty()) {
      t.names = cells;
      t.cols.resize(cells.size());
      continue;
    }
    if (cells.size() != t.names.size()) throw Error(fmt::format("{}: a row has {} columns, the header {}", path, cells.size(), t.names.size()));
    for (size_t c = 0; c < cells.size(); ++c) t.cols[c].push_back(std::strtod(cells[c].c_str(), nullptr));
  }
  return t;
}

}  // namespace

io::Metrics run_metrics(const std::string& dir, const DemSolver& dem, bool with_diagnostics,
                        std::optional<std::pair<double, double>> front_impact) {
  return run_metrics(dir, dem.time(), static_cast<long>(dem.particles().size()), dem.energy(), dem.removed(),
                     with_diagnostics, front_impact);
}

io::Metrics run_metrics(const std::string& dir, double t, long particles, const EnergyBudget& e, long removed,
                        bool with_diagnostics, std::optional<std::pair<double, double>> front_impact) {
  io::Metrics m{{"end_time_s", t},
                {"particles", double(particles)},
                {"solid_mass_kg", e.mass},
                {"E_kin_trans_J", e.kinetic_translational},
                {"removed", double(removed)}};
  if (!with_diagnostics) return m;
  for (auto& kv : die_metrics(dir + "/diagnostics.csv", front_impact)) m.push_back(kv);
  return m;
}

io::Metrics die_metrics(const std::string& file, std::optional<std::pair<double, double>> front_impact) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  io::Metrics m;
  const Table t = read_table(file);
  const auto& time = t.col("t", file);
  if (time.empty()) throw Error(file + ": no rows");
  const double t_from = time.front() < 0 ? 0.0 : time.front();
  // Largest value of a column over t >= t_from: (value, time); NaN rows are skipped.
  auto peak = [&](const std::vector<double>& v) {
    double best = -std::numeric_limits<double>::infinity(), at = nan;
    for (size_t r = 0; r < v.size(); ++r)
      if (time[r] >= t_from && std::isfinite(v[r]) && v[r] > best) best = v[r], at = time[r];
    return std::make_pair(std::isfinite(best) ? best : nan, at);
  };
  m.emplace_back("front_time_s", front_impact ? front_impact->first : nan);
  m.emplace_back("mean_impact_velocity_m_s", front_impact ? front_impact->second : nan);
  m.emplace_back("fill_mass_kg", t.col("mass_in_die", file).back());
  const auto [rate, rate_t] = peak(t.col("transfer_rate", file));
  m.emplace_back("transfer_rate_peak_kg_s", rate);
  m.emplace_back("transfer_rate_peak_time_s", rate_t);
  auto has = [&](const char* n) { return std::find(t.names.begin(), t.names.end(), n) != t.names.end(); };
  if (has("mass_in_shoe")) m.emplace_back("shoe_mass_end_kg", t.col("mass_in_shoe", file).back());
  for (const auto& [column, metric] : {std::pair{"V_bubble_max", "bubble_volume"}, {"V_bubbles_shoe", "bubble_in_shoe"}}) {
    if (!has(column)) continue;
    const auto [v, v_t] = peak(t.col(column, file));
    m.emplace_back(std::string(metric) + "_peak_m3", v);
    m.emplace_back(std::string(metric) + "_peak_time_s", v_t);
  }
  for (size_t c = 0; c < t.names.size(); ++c) {
    if (t.names[c].rfind("p_", 0) != 0) continue;
    const auto [p, p_t] = peak(t.cols[c]);
    double sum = 0;
    long n = 0;
    for (size_t r = 0; r < time.size(); ++r)
      if (time[r] >= t_from && std::isfinite(t.cols[c][r])) sum += t.cols[c][r], ++n;
    m.emplace_back(t.names[c] + "_peak_Pa", p);
    m.emplace_back(t.names[c] + "_peak_time_s", p_t);
    m.emplace_back(t.names[c] + "_mean_Pa", n ? sum / n : nan);
  }
  return m;
}

}  // namespace cgdem::app
