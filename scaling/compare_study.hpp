// `cgdem compare`: two or more finished runs of `cgdem run` side by side (the same case
// with and without air, say), read from their folders:
//
//   * config.resolved.toml: the git revision (first line; else diagnostics.csv's "# cgdem
//     <revision>, ..." line) and every resolved key, flattened
//     to key paths (`air.enabled`, `diagnostics.pressure_cell[1].max`); the keys whose values
//     are not the same in every run are the runs' configuration difference. Optional.
//   * metrics.csv: every metric of any run, in the order first met; a NaN value or a metric a
//     run did not write is missing. Against the first run i = 0: d_i = v_i - v_0 and
//     r_i = d_i / |v_0| (missing when v_0 = 0, unless v_i = 0 too: then 0).
//   * diagnostics.csv: every numeric column besides `t` (mass_in_die, transfer_rate, p_A ...
//     and whatever else a run writes: columns are taken by name from each file). A restarted
//     run's superseded rows (at or after the restart time) are dropped, as in
//     spectrum_series.hpp. The common time range is [max of the first times, min of the last
//     times] of all runs (narrowed by --from/--to); each curve is resampled linearly
//     (series.hpp) at the multiples of dt inside it, and its distance from the first run's
//     curve is measured on the first run's own samples inside the range:
//       normalized L2  D_2 = sqrt( sum_j w_j (y_j - y0_j)^2 / sum_j w_j y0_j^2 )
//       max deviation  D_inf = max_j |y_j - y0_j| (in the column's unit)
//     w_j trapezoidal weights; samples where either value is NaN are left out. D_2 is missing
//     when no sample is finite in both or the first run's curve is zero there.
//
// Units: metrics by their SI suffix (io/metrics.hpp); diagnostics columns from their
// description lines (io/csv_series.hpp), the curves named by quantity (mass_in_die for
// mass_in_die_kg, p_A for p_A_Pa) so that runs written before the names carried units
// compare with those written after; for those, by the die-filling conventions (column_unit).
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/metrics.hpp"
#include "scaling/csv_table.hpp"

namespace cgdem::scaling {

struct CompareRun {
  std::string dir, label;
  std::string revision;   // "" when neither config.resolved.toml nor diagnostics.csv names one
  std::string case_file;  // from config.resolved.toml's first line, "" if unknown
  bool has_config = false;
  std::map<std::string, std::string> config;  // key path -> TOML value text
  io::Metrics metrics;                        // as written (NaN kept)
  CsvTable diagnostics;                       // superseded restart rows dropped
};

// Reads a run folder. Throws cgdem::Error naming the folder and the file when the folder, its
// metrics.csv or its diagnostics.csv is missing or malformed, or diagnostics.csv has no `t`.
CompareRun read_compare_run(const std::string& dir, const std::string& label);

// Resolved TOML text -> key path -> value text (tables joined with '.', arrays of tables
// indexed [i], other arrays written inline). Throws cgdem::Error naming `source` on bad TOML.
std::map<std::string, std::string> flatten_toml(const std::string& text, const std::string& source);

struct ConfigDifference {
  std::string key;
  std::vector<std::optional<std::string>> values;  // per run; nullopt: the run has no such key
};
// Keys (sorted) whose value differs between the runs that have a config.resolved.toml.
std::vector<ConfigDifference> config_differences(const std::vector<CompareRun>& runs);

// "kg", "kg/s", "s", "Pa", "m^3/s" ... or "" when not known.
std::string metric_unit(const std::string& name);
std::string column_unit(const std::string& column);
// The CSV column name with its unit: mass_in_die -> mass_in_die_kg, transfer_rate ->
// transfer_rate_kg_s, p_A -> p_A_Pa, t -> t_s (unchanged without a known unit).
std::string column_with_unit(const std::string& column);

struct MetricComparison {
  std::string name, unit;
  std::vector<double> value, abs_diff, rel_diff;  // per run; NaN = missing (index 0 diffs NaN)
};
std::vector<MetricComparison> compare_metrics(const std::vector<CompareRun>& runs);

struct CurveComparison {
  std::string column, unit;
  std::vector<std::vector<double>> sampled;    // [run][sample time]; NaN where missing
  std::vector<double> l2, max_abs, t_max_abs;  // per run against run 0 (index 0 NaN)
  std::vector<size_t> points;                  // first-run samples both finite, per run
};

struct CurveSettings {
  double dt = 0.02;                // s, between the sampled times
  std::optional<double> from, to;  // s, narrow the common range
};

struct Curves {
  double t_lo = 0, t_hi = 0, dt = 0;  // the common range and the sampling interval
  std::vector<double> times;          // sample times
  size_t reference_points = 0;        // first-run samples in [t_lo, t_hi]
  std::vector<CurveComparison> curves;
  std::vector<std::string> no_values;  // columns present but without a finite value in any run
};
// Throws cgdem::Error when the runs have no common time range (naming each run's span), or
// dt is not positive.
Curves compare_curves(const std::vector<CompareRun>& runs, const CurveSettings& s);

struct Comparison {
  std::vector<CompareRun> runs;
  std::vector<ConfigDifference> config;
  std::vector<MetricComparison> metrics;
  Curves curves;
};

// At least two folders; labels (default: the folders' names) must be as many as the folders
// and distinct. Throws cgdem::Error on any bad input.
Comparison compare_runs(const std::vector<std::string>& dirs, const std::vector<std::string>& labels,
                        const CurveSettings& s);

// The folder's name ("out/with_air/" -> "with_air").
std::string folder_name(const std::string& dir);

}  // namespace cgdem::scaling
