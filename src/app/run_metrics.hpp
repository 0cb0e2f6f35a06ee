// metrics.csv of a run (io/metrics.hpp): the scalar observables, written at the end of a
// run from its time series on disk (so a restarted run reports the whole history).
//
// Every run:      end_time_s, particles, solid_mass_kg, E_kin_trans_J (final), removed
// Die filling:    front_time_s, mean_impact_velocity_m_s (docs/model.md, section 6; NaN before
//                 the front reaches the floor), fill_mass_kg (solid mass in the die at the
//                 end), shoe_mass_end_kg (with the shoe columns), and over the filling
//                 window (below):
//                   window_from_s, window_to_s      the window itself
//                   transfer_rate_peak_kg_s / _time_s
//                   p_X_peak_Pa, p_X_peak_time_s, p_X_mean_Pa  for each pressure cell X
//                   bubble_volume_peak_m3 / _time_s (largest bubble), bubble_in_shoe_peak_m3 /
//                   _time_s (bubble air above the table top)
//
// Filling window. The die fills while the shoe's cavity lies over its mouth (docs/model.md,
// section 4, Timeline): from t_open, when the cavity's leading edge reaches the mouth
// (0.05 s for the paper's geometry: the pressure climbs "from the moment filling starts"),
// to t_close, when its trailing edge passes the far end of the mouth (0.25 s), both from
// DieFillingParams::shoe_motion(); clipped to the rows of the file. Before t_open the die is
// closed: what the cells show then is the settling and the start-up of the air and of the
// shoe (in Case 1-3 a 0.8 ms spike of p_C at the first fluid steps of the motion), not
// filling. Without the geometry (die_metrics(file, front) alone) the window is t >= 0 (the
// shoe's motion; the settling before it excluded) to the last row.
//
// Not computed: a metric that cannot be computed is left out of the file, never written as
// NaN: every pressure and bubble metric of a run without air, and any windowed metric whose
// column has no finite value in the window (a cell box holding no air cell; a run that ends
// before the die opens). Readers show such a metric as "not computed" (io::may_be_left_out).
//
// Column names: the diagnostics columns are found with or without a unit suffix (`t` or
// `t_s`, `p_A` or `p_A_Pa`, `transfer_rate` or `transfer_rate_kg_per_s` ...), so files of
// either layout give the same metric names.
#pragma once
#include <optional>
#include <string>
#include <utility>

#include "geometry/die_filling.hpp"
#include "io/metrics.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

// The times the die opens and closes (see above) [s]; +inf when the shoe never gets there.
struct FillingWindow {
  double from = 0, to = 0;
};
FillingWindow filling_window(const geometry::DieFillingParams& die);

// What the metrics need to know of the run besides diagnostics.csv.
struct DieRun {
  geometry::DieFillingParams die;  // the filling window
  bool with_air = true;            // pressure and bubble metrics only with air
};

// The die-filling metrics from a diagnostics.csv file (see above).
io::Metrics die_metrics(const std::string& diagnostics_csv, std::optional<std::pair<double, double>> front_impact,
                        const std::optional<DieRun>& run = std::nullopt);

// Reads DIR/diagnostics.csv (if `with_diagnostics`) and returns the metrics, with those of
// the run's end from its totals (over the ranks: e = the energy budget of every parcel,
// the counts over the ranks).
io::Metrics run_metrics(const std::string& dir, double t, long particles, const EnergyBudget& e, long removed,
                        bool with_diagnostics, std::optional<std::pair<double, double>> front_impact,
                        const std::optional<DieRun>& run = std::nullopt);

}  // namespace cgdem::app
