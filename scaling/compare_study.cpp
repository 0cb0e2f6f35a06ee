#include "scaling/compare_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <toml.hpp>

#include "core/error.hpp"
#include "scaling/series.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string first_line_of(const fs::path& p) {
  std::ifstream in(p);
  std::string l;
  std::getline(in, l);
  if (!l.empty() && l.back() == '\r') l.pop_back();
  return l;
}

// "# cgdem <revision>[,] ..." -> <revision>.
std::string revision_in(const std::string& comment) {
  const std::string tag = "# cgdem ";
  if (comment.rfind(tag, 0) != 0) return "";
  std::string rev = comment.substr(tag.size());
  rev = rev.substr(0, rev.find(' '));
  if (!rev.empty() && rev.back() == ',') rev.pop_back();
  return rev;
}

// A restarted run continues diagnostics.csv from its checkpoint: the rows of the interrupted
// run at or after the restart time are superseded by the new ones.
void drop_superseded_rows(CsvTable& c) {
  const auto& t = c.col("t");
  std::vector<size_t> keep;
  for (size_t r = 0; r < t.size(); ++r) {
    if (!std::isfinite(t[r])) throw Error(fmt::format("{}: data row {}: t is not a number", c.source, r + 1));
    while (!keep.empty() && t[keep.back()] >= t[r]) keep.pop_back();
    keep.push_back(r);
  }
  for (auto& col : c.columns) {
    std::vector<double> kept(keep.size());
    for (size_t k = 0; k < keep.size(); ++k) kept[k] = col[keep[k]];
    col = std::move(kept);
  }
}

std::string toml_text(const toml::value& v) {
  if (v.is_boolean()) return v.as_boolean() ? "true" : "false";
  if (v.is_integer()) return fmt::format("{}", v.as_integer());
  if (v.is_floating()) {
    std::string s = fmt::format("{}", v.as_floating());
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // 1 -> 1.0 (nan, inf kept)
    return s;
  }
  if (v.is_string()) return fmt::format("\"{}\"", v.as_string().str);
  if (v.is_array()) {
    std::vector<std::string> items;
    for (const auto& e : v.as_array()) items.push_back(toml_text(e));
    return fmt::format("[{}]", fmt::join(items, ", "));
  }
  std::ostringstream s;  // dates, inline tables
  s << toml::format(v, 0);
  return s.str();
}

void flatten(const toml::value& v, const std::string& path, std::map<std::string, std::string>& out) {
  const auto tables_only = [](const toml::array& a) {
    return !a.empty() && std::all_of(a.begin(), a.end(), [](const toml::value& e) { return e.is_table(); });
  };
  if (v.is_table()) {
    for (const auto& [k, e] : v.as_table()) flatten(e, path.empty() ? k : path + "." + k, out);
  } else if (v.is_array() && tables_only(v.as_array())) {
    for (size_t i = 0; i < v.as_array().size(); ++i) flatten(v.as_array()[i], fmt::format("{}[{}]", path, i), out);
  } else {
    out[path] = toml_text(v);
  }
}

double value_of(const io::Metrics& m, const std::string& name) {
  for (const auto& [k, v] : m)
    if (k == name) return v;
  return kNaN;
}

// The run's time span [first, last] of diagnostics.csv.
std::pair<double, double> span_of(const CompareRun& r) {
  const auto& t = r.diagnostics.col("t");
  if (t.empty()) throw Error(fmt::format("{}: no data rows", r.diagnostics.source));
  return {t.front(), t.back()};
}

bool has_finite(const CompareRun& r, const std::string& column) {
  if (!r.diagnostics.has(column)) return false;
  const auto& y = r.diagnostics.col(column);
  return std::any_of(y.begin(), y.end(), [](double v) { return std::isfinite(v); });
}

std::vector<double> sampled(const CompareRun& r, const std::string& column, const std::vector<double>& times) {
  if (!r.diagnostics.has(column)) return std::vector<double>(times.size(), kNaN);
  return resample(Series{r.diagnostics.col("t"), r.diagnostics.col(column)}, times);
}

// The distances of run i's curve from the reference's on the reference's samples `t`.
void distances(const std::vector<double>& t, const std::vector<double>& ref, const std::vector<double>& y,
               CurveComparison& c, size_t i) {
  std::vector<double> tt, a, b;
  for (size_t j = 0; j < t.size(); ++j)
    if (std::isfinite(ref[j]) && std::isfinite(y[j])) tt.push_back(t[j]), a.push_back(ref[j]), b.push_back(y[j]);
  c.points[i] = tt.size();
  if (tt.empty()) return;
  c.l2[i] = normalized_l2(tt, b, a);
  const MaxDeviation m = max_abs_deviation(b, a);
  c.max_abs[i] = m.value;
  c.t_max_abs[i] = tt[m.index];
}

}  // namespace

std::string folder_name(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..") name = fs::absolute(p).lexically_normal().filename().string();
  return name;
}

std::map<std::string, std::string> flatten_toml(const std::string& text, const std::string& source) {
  toml::value doc;
  try {
    std::istringstream in(text);
    doc = toml::parse(in, source);
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: {}", source, e.what()));
  }
  std::map<std::string, std::string> out;
  flatten(doc, "", out);
  return out;
}

CompareRun read_compare_run(const std::string& dir, const std::string& label) {
  const fs::path d(dir);
  if (!fs::is_directory(d)) throw Error(fmt::format("compare: run folder '{}' does not exist", dir));
  const std::pair<const char*, const char*> needed[] = {
      {"metrics.csv", "cgdem run writes it when the run ends: did it finish?"},
      {"diagnostics.csv", "cgdem run writes it for a case with [walls.die_filling]"}};
  for (const auto& [file, why] : needed)
    if (!fs::is_regular_file(d / file))
      throw Error(fmt::format("compare: run folder '{}' has no {} ({})", dir, file, why));
  CompareRun r;
  r.dir = dir;
  r.label = label;
  r.metrics = io::read_metrics((d / "metrics.csv").string());
  r.diagnostics = read_csv_table((d / "diagnostics.csv").string());
  if (!r.diagnostics.has("t"))
    throw Error(
        fmt::format("{}: no column 't' (it has: {})", r.diagnostics.source, fmt::join(r.diagnostics.names, ", ")));
  drop_superseded_rows(r.diagnostics);
  const fs::path cfg = d / "config.resolved.toml";
  if (fs::is_regular_file(cfg)) {
    std::ifstream in(cfg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    r.config = flatten_toml(text, cfg.string());
    r.has_config = true;
    const std::string head = first_line_of(cfg), of = " resolved configuration of ";
    r.revision = revision_in(head);
    if (const auto k = head.find(of); k != std::string::npos) r.case_file = head.substr(k + of.size());
  }
  if (r.revision.empty()) r.revision = r.diagnostics.revision();  // its "# cgdem <revision>, ..." line
  return r;
}

std::vector<ConfigDifference> config_differences(const std::vector<CompareRun>& runs) {
  std::set<std::string> keys;
  for (const auto& r : runs)
    for (const auto& [k, v] : r.config) keys.insert(k);
  std::vector<ConfigDifference> out;
  for (const auto& k : keys) {
    ConfigDifference d{k, {}};
    std::set<std::optional<std::string>> seen;
    for (const auto& r : runs) {
      const auto it = r.config.find(k);
      d.values.push_back(it == r.config.end() ? std::nullopt : std::optional<std::string>(it->second));
      if (r.has_config) seen.insert(d.values.back());
    }
    if (seen.size() > 1) out.push_back(std::move(d));
  }
  return out;
}

std::string metric_unit(const std::string& name) {
  // Longest suffix first: _kg_s before _s, _m3_s before _s and _m3, _m_s before _s.
  static const std::pair<const char*, const char*> suffixes[] = {
      {"_kg_s", "kg/s"}, {"_m3_s", "m^3/s"}, {"_m_s", "m/s"}, {"_Pa", "Pa"}, {"_kg", "kg"},
      {"_m3", "m^3"},    {"_J", "J"},        {"_s", "s"},     {"_m", "m"},   {"_Hz", "Hz"}};
  for (const auto& [suffix, unit] : suffixes) {
    const std::string s = suffix;
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) return unit;
  }
  return "";
}

std::string column_unit(const std::string& c) {
  const auto starts = [&](const char* p) { return c.rfind(p, 0) == 0; };
  if (c == "t") return "s";
  if (c == "transfer_rate") return "kg/s";
  if (starts("mass_")) return "kg";
  if (starts("p_")) return "Pa";
  if (starts("Q_")) return "m^3/s";
  if (starts("V_")) return "m^3";
  if (starts("z_")) return "m";
  return "";
}

std::string column_with_unit(const std::string& c) {
  std::string u = column_unit(c);
  if (u.empty()) return c;
  std::replace(u.begin(), u.end(), '/', '_');
  u.erase(std::remove(u.begin(), u.end(), '^'), u.end());
  return c + "_" + u;
}

std::vector<MetricComparison> compare_metrics(const std::vector<CompareRun>& runs) {
  std::vector<std::string> names;
  for (const auto& r : runs)
    for (const auto& [k, v] : r.metrics)
      if (std::find(names.begin(), names.end(), k) == names.end()) names.push_back(k);
  std::vector<MetricComparison> out;
  for (const auto& n : names) {
    MetricComparison m{n, metric_unit(n), {}, {}, {}};
    for (const auto& r : runs) m.value.push_back(value_of(r.metrics, n));
    const double v0 = m.value[0];
    for (double v : m.value) {
      const double d = std::isfinite(v0) && std::isfinite(v) ? v - v0 : kNaN;
      m.abs_diff.push_back(d);
      m.rel_diff.push_back(std::isnan(d) ? kNaN : v0 != 0 ? d / std::fabs(v0) : d == 0 ? 0.0 : kNaN);
    }
    m.abs_diff[0] = m.rel_diff[0] = kNaN;
    out.push_back(std::move(m));
  }
  return out;
}

namespace {

// The runs' common time range (narrowed by --from/--to; at most 10,000 rows of --dt) into
// c.t_lo and c.t_hi; returns each run's sample times (to be joined into common times).
std::vector<Series> common_range(const std::vector<CompareRun>& runs, const CurveSettings& s, Curves& c) {
  c.t_lo = -std::numeric_limits<double>::infinity();
  c.t_hi = std::numeric_limits<double>::infinity();
  std::vector<std::string> spans;
  std::vector<Series> all;
  for (const auto& r : runs) {
    const auto [a, b] = span_of(r);
    c.t_lo = std::max(c.t_lo, a);
    c.t_hi = std::min(c.t_hi, b);
    spans.push_back(fmt::format("{} {:g} to {:g} s", r.label, a, b));
    all.push_back({r.diagnostics.col("t"), {}});
  }
  if (s.from) c.t_lo = std::max(c.t_lo, *s.from);
  if (s.to) c.t_hi = std::min(c.t_hi, *s.to);
  if (!(c.t_hi > c.t_lo))
    throw Error(fmt::format("compare: the runs have no common time range{} (diagnostics.csv: {})",
                            s.from || s.to ? " within --from/--to" : "", fmt::join(spans, ", ")));
  if ((c.t_hi - c.t_lo) / s.dt > 1e4)
    throw Error(fmt::format("--dt: {:g} s gives more than 10,000 rows over {:g} to {:g} s; give a larger one", s.dt,
                            c.t_lo, c.t_hi));
  return all;
}

// The sample times into c.times: the multiples of dt inside [t_lo, t_hi] (both ends when none
// is), as k / n when dt = 1/n (7 / 50 = 0.14, where 7 * 0.02 = 0.14000000000000001).
void sample_times(const CurveSettings& s, Curves& c) {
  const double eps = 1e-9, per_s = std::round(1 / s.dt);
  const bool whole = per_s >= 1 && std::fabs(1 / s.dt - per_s) < eps * per_s;
  for (auto k = static_cast<long>(std::ceil(c.t_lo / s.dt - eps));
       k <= static_cast<long>(std::floor(c.t_hi / s.dt + eps)); ++k)
    c.times.push_back(
        std::clamp(whole ? static_cast<double>(k) / per_s : static_cast<double>(k) * s.dt, c.t_lo, c.t_hi));
  if (c.times.empty()) c.times = {c.t_lo, c.t_hi};
}

// The curves by quantity (mass_in_die, p_A: the names without their unit suffix, so that runs
// written before the names carried units compare with those written after), in the order
// the runs first name them, and their units (from the files, or from the quantity's name).
std::pair<std::vector<std::string>, std::vector<std::string>> quantities(const std::vector<CompareRun>& runs) {
  std::vector<std::string> columns, units;
  for (const auto& r : runs)
    for (size_t k = 0; k < r.diagnostics.names.size(); ++k) {
      const std::string q = r.diagnostics.quantity(k);
      if (q == "t" || std::find(columns.begin(), columns.end(), q) != columns.end()) continue;
      columns.push_back(q);
      units.push_back(r.diagnostics.units[k] == "1" ? "" : r.diagnostics.units[k]);
    }
  for (size_t k = 0; k < columns.size(); ++k)
    if (units[k].empty()) units[k] = column_unit(columns[k]);
  return {columns, units};
}

}  // namespace

Curves compare_curves(const std::vector<CompareRun>& runs, const CurveSettings& s) {
  if (!(s.dt > 0) || !std::isfinite(s.dt)) throw Error(fmt::format("--dt: {} s is not a positive interval", s.dt));
  Curves c;
  c.dt = s.dt;
  std::vector<Series> all = common_range(runs, s, c);
  sample_times(s, c);
  // The first run's own samples in the range (the window joins the spans as one more series).
  all.push_back({{c.t_lo, c.t_hi}, {}});
  const std::vector<double> ref_t = common_times(runs[0].diagnostics.col("t"), all);
  c.reference_points = ref_t.size();
  const auto [columns, units] = quantities(runs);
  // Per quantity with a finite value in some run: the curves on c.times and their distances
  // to the first run's on its own times.
  for (size_t q = 0; q < columns.size(); ++q) {
    const std::string& col = columns[q];
    if (std::none_of(runs.begin(), runs.end(), [&](const CompareRun& r) { return has_finite(r, col); })) {
      c.no_values.push_back(col);
      continue;
    }
    const size_t n = runs.size();
    CurveComparison k{col,
                      units[q],
                      {},
                      std::vector<double>(n, kNaN),
                      std::vector<double>(n, kNaN),
                      std::vector<double>(n, kNaN),
                      std::vector<size_t>(n, 0)};
    try {
      for (const auto& r : runs) k.sampled.push_back(sampled(r, col, c.times));
      const std::vector<double> ref = sampled(runs[0], col, ref_t);
      for (size_t i = 1; i < n; ++i) distances(ref_t, ref, sampled(runs[i], col, ref_t), k, i);
    } catch (const Error& e) {
      throw Error(fmt::format("compare: column {}: {}", col, e.what()));
    }
    c.curves.push_back(std::move(k));
  }
  return c;
}

Comparison compare_runs(const std::vector<std::string>& dirs, const std::vector<std::string>& labels,
                        const CurveSettings& s) {
  if (dirs.size() < 2)
    throw Error(fmt::format("compare: give at least two run folders (got {}): cgdem compare RUN_A RUN_B", dirs.size()));
  if (!labels.empty() && labels.size() != dirs.size())
    throw Error(fmt::format("--labels: {} label(s) for {} run folders", labels.size(), dirs.size()));
  Comparison c;
  for (size_t i = 0; i < dirs.size(); ++i) {
    const std::string label = labels.empty() ? folder_name(dirs[i]) : labels[i];
    if (label.empty() || label.find_first_of(",\n\r\"") != std::string::npos)
      throw Error(fmt::format("--labels: '{}' (for {}) is not a usable label: not empty, no comma, quote or newline",
                              label, dirs[i]));
    for (const auto& r : c.runs)
      if (r.label == label)
        throw Error(fmt::format("compare: '{}' and '{}' have the same label '{}'; name the runs with --labels a,b,...",
                                r.dir, dirs[i], label));
    c.runs.push_back(read_compare_run(dirs[i], label));
  }
  c.config = config_differences(c.runs);
  c.metrics = compare_metrics(c.runs);
  c.curves = compare_curves(c.runs, s);
  return c;
}

}  // namespace cgdem::scaling
