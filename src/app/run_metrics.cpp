#include "app/run_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace cgdem::app {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Whether `rest` is a unit suffix: '_'-separated tokens of SI units ("s", "kg_per_s", "m3_s", "Pa", "1").
bool is_unit_suffix(const std::string& rest) {
  static const char* const units[] = {"s", "kg", "m", "m2", "m3", "Pa", "J", "N", "W", "per", "1", "Hz", "rad"};
  if (rest.empty()) return false;
  std::istringstream ss(rest);
  for (std::string tok; std::getline(ss, tok, '_');)
    if (std::none_of(std::begin(units), std::end(units), [&](const char* u) { return tok == u; })) return false;
  return rest.back() != '_';
}

// Whether the column `name` is the quantity `base`, with or without a unit suffix.
bool is_column(const std::string& name, const std::string& base) {
  return name == base || (name.size() > base.size() + 1 && name.compare(0, base.size(), base) == 0 &&
                          name[base.size()] == '_' && is_unit_suffix(name.substr(base.size() + 1)));
}

// Columns of a CSV written by a run ('#' comment lines skipped, before or after the column line), by name.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  const std::vector<double>* find(const std::string& base) const {
    for (size_t c = 0; c < names.size(); ++c)
      if (is_column(names[c], base)) return &cols[c];
    return nullptr;
  }
  const std::vector<double>& col(const std::string& base, const std::string& file) const {
    if (const auto* c = find(base)) return *c;
    throw Error(fmt::format("{}: no column '{}' (nor '{}_<unit>')", file, base, base));
  }
};

Table read_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read " + path);
  Table t;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cells;
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (t.names.empty()) {
      t.names = cells;
      t.cols.resize(cells.size());
      continue;
    }
    if (cells.size() != t.names.size())
      throw Error(fmt::format("{}:{}: a row has {} columns, the header {}", path, n, cells.size(), t.names.size()));
    for (size_t c = 0; c < cells.size(); ++c) t.cols[c].push_back(std::strtod(cells[c].c_str(), nullptr));
  }
  return t;
}

// The time at which the shoe's displacement along x reaches d [s]: 0 when d <= 0 (the
// cavity is there from the start), +inf when the shoe never gets there. The displacement
// is non-decreasing (speed >= 0), so bisection finds the first such time.
double time_of_displacement(const geometry::Motion& m, const geometry::DieFillingParams& p, double d) {
  if (d <= 0) return 0.0;
  if (!(p.shoe_speed > 0)) return std::numeric_limits<double>::infinity();
  double lo = p.shoe_start, hi = p.shoe_start + p.shoe_ramp + d / p.shoe_speed + 1.0;
  while (m.displacement(hi).x < d) hi *= 2;  // guards a motion slower than its nominal speed
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (m.displacement(mid).x < d ? lo : hi) = mid;
  }
  return hi;
}

// The largest value of v over the rows with from <= t <= to and its time; nullopt when no
// such row holds a finite value.
std::optional<std::pair<double, double>> peak_in(const std::vector<double>& t, const std::vector<double>& v,
                                                 double from, double to) {
  double best = -std::numeric_limits<double>::infinity(), at = kNaN;
  for (size_t r = 0; r < v.size(); ++r)
    if (t[r] >= from && t[r] <= to && std::isfinite(v[r]) && v[r] > best) best = v[r], at = t[r];
  if (!std::isfinite(best)) return std::nullopt;
  return std::make_pair(best, at);
}

std::optional<double> mean_in(const std::vector<double>& t, const std::vector<double>& v, double from, double to) {
  double sum = 0;
  long n = 0;
  for (size_t r = 0; r < v.size(); ++r)
    if (t[r] >= from && t[r] <= to && std::isfinite(v[r])) sum += v[r], ++n;
  if (n == 0) return std::nullopt;
  return sum / n;
}

// A pressure column's cell name: "p_A" or "p_A_Pa" -> "A"; empty when not a pressure column.
std::string pressure_cell(const std::string& column) {
  if (column.rfind("p_", 0) != 0 || column.size() < 3) return "";
  std::string cell = column.substr(2);
  if (cell.size() > 3 && cell.compare(cell.size() - 3, 3, "_Pa") == 0) cell.resize(cell.size() - 3);
  return cell;
}

}  // namespace

FillingWindow filling_window(const geometry::DieFillingParams& p) {
  const geometry::Motion m = p.shoe_motion();
  const double lead = p.cavity_x0 + p.cavity_size.x;  // the cavity's leading (right) edge at t = 0
  // Open: the leading edge reaches the mouth; closed: the trailing edge passes its far end.
  return {time_of_displacement(m, p, p.mouth_x0 - lead),
          time_of_displacement(m, p, p.mouth_x0 + p.mouth_length - p.cavity_x0)};
}

io::Metrics run_metrics(const std::string& dir, double t, long particles, const EnergyBudget& e, long removed,
                        bool with_diagnostics, std::optional<std::pair<double, double>> front_impact,
                        const std::optional<DieRun>& run) {
  io::Metrics m{{"end_time_s", t},
                {"particles", double(particles)},
                {"solid_mass_kg", e.mass},
                {"E_kin_trans_J", e.kinetic_translational},
                {"removed", double(removed)}};
  if (!with_diagnostics) return m;
  for (auto& kv : die_metrics(dir + "/diagnostics.csv", front_impact, run)) m.push_back(kv);
  return m;
}

io::Metrics die_metrics(const std::string& file, std::optional<std::pair<double, double>> front_impact,
                        const std::optional<DieRun>& run) {
  io::Metrics m;
  const Table t = read_table(file);
  const auto& time = t.col("t", file);
  if (time.empty()) throw Error(file + ": no rows");
  // The filling window, clipped to the file's rows.
  double from = std::max(0.0, time.front()), to = time.back();
  if (run) {
    const FillingWindow w = filling_window(run->die);
    from = std::max(w.from, time.front());
    to = std::min(w.to, time.back());
  }
  const bool with_air = !run || run->with_air;

  m.emplace_back("front_time_s", front_impact ? front_impact->first : kNaN);
  m.emplace_back("mean_impact_velocity_m_s", front_impact ? front_impact->second : kNaN);
  m.emplace_back("fill_mass_kg", t.col("mass_in_die", file).back());
  if (const auto* shoe = t.find("mass_in_shoe")) m.emplace_back("shoe_mass_end_kg", shoe->back());
  m.emplace_back("window_from_s", from);
  m.emplace_back("window_to_s", to);
  // A peak (value and time) over the window, left out when not computable.
  auto add_peak = [&](const std::vector<double>& v, const std::string& value_name, const std::string& time_name) {
    if (const auto pk = peak_in(time, v, from, to)) {
      m.emplace_back(value_name, pk->first);
      m.emplace_back(time_name, pk->second);
    }
  };
  add_peak(t.col("transfer_rate", file), "transfer_rate_peak_kg_s", "transfer_rate_peak_time_s");
  if (with_air)
    for (const auto& [column, metric] : {std::pair{"V_bubble_max", "bubble_volume"}, {"V_bubbles_shoe", "bubble_in_shoe"}})
      if (const auto* v = t.find(column))
        add_peak(*v, std::string(metric) + "_peak_m3", std::string(metric) + "_peak_time_s");
  for (size_t c = 0; c < t.names.size() && with_air; ++c) {
    const std::string cell = pressure_cell(t.names[c]);
    if (cell.empty()) continue;
    add_peak(t.cols[c], "p_" + cell + "_peak_Pa", "p_" + cell + "_peak_time_s");
    if (const auto mean = mean_in(time, t.cols[c], from, to)) m.emplace_back("p_" + cell + "_mean_Pa", *mean);
  }
  return m;
}

}  // namespace cgdem::app
