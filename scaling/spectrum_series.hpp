// The pressure series of a run folder for `cgdem spectrum`: diagnostics.csv (written by
// `cgdem run` with [walls.die_filling]) starts with the column line `t_s,...,p_<cell>_Pa,...`,
// then '#' lines (provenance, the columns' units and descriptions: io/csv_series.hpp) and
// one row per output time. The pressure columns are found by their `p_` prefix and `_Pa`
// suffix, any number of them. Files written before the names carried units ('#' lines,
// then `t,...,p_<cell>,...`) are read too. When the file states its row grid ("# rows: at t =
// T0 s + k DT s", app/run_schedule.hpp), a row off it (the final state of a run whose
// time.end is not on the grid) is left out.
//
// Uniform sampling: the spectra (spectrum.hpp) assume x[n] = x(t_0 + n dt). The intervals
// t[i+1] - t[i] must equal their median dt within a relative 1e-3 (a timing jitter below
// 0.1 % of dt is a phase error well below the estimator's own scatter); otherwise a clear
// error names the first bad interval. `resample` puts a series on an exactly uniform grid
// by linear interpolation (for output times that drift by a solver step, or to bring runs
// written at different intervals onto one grid); linear interpolation is a low-pass filter
// (gain sinc^2(f dt_old) at most), harmless well below the Nyquist frequency of the data.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace cgdem::scaling {

struct PressureSeries {
  std::string source;                  // the file read
  std::vector<double> t;               // s
  std::vector<std::string> cells;      // cell names (the columns without the `p_` prefix)
  std::vector<std::vector<double>> p;  // p[cell][sample], Pa
};

// Reads RUN_DIR/diagnostics.csv. Error on a missing folder or file, no `t` or `p_` column,
// a malformed or non-finite value, or fewer than 2 rows.
PressureSeries read_pressure_series(const std::string& run_dir);

// The rows with from <= t <= to, and the named cells in the given order (all cells when
// `cells` is empty). Error on an unknown cell (listing those the run has) or an empty range.
PressureSeries select(const PressureSeries& s, const std::vector<std::string>& cells, std::optional<double> from,
                      std::optional<double> to);

// The sampling interval: the median of t[i+1] - t[i]. Error when t does not increase or an
// interval differs from it by more than rel_tol (naming the interval and suggesting --dt).
double uniform_interval(const PressureSeries& s, double rel_tol = 1e-3);

// Linear interpolation onto t_0 + n dt, n = 0 .. floor((t_end - t_0)/dt) (Error on dt <= 0).
PressureSeries resample(const PressureSeries& s, double dt);

}  // namespace cgdem::scaling
