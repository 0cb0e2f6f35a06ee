// metrics.csv of a run (io/metrics.hpp): the scalar observables, written at the end of a
// run from its time series on disk (so a restarted run reports the whole history).
//
// Every run:      end_time_s, particles, solid_mass_kg, E_kin_trans_J (final), removed
// Die filling:    front_time_s, mean_impact_velocity_m_s (docs/model.md, section 6; NaN before
//                 the front reaches the floor), fill_mass_kg (solid mass in the die at the
//                 end), transfer_rate_peak_kg_s and transfer_rate_peak_time_s, and for each
//                 pressure cell X: p_X_peak_Pa and p_X_peak_time_s (largest gauge pressure)
//                 and p_X_mean_Pa; with the shoe and air-path columns: shoe_mass_end_kg,
//                 bubble_volume_peak_m3 / _time_s (largest bubble), bubble_in_shoe_peak_m3 / _time_s
//                 (bubble air above the table top). Peaks are taken over t >= 0 (the shoe's motion; the
//                 settling before it is excluded) and over the whole run if it starts later.
#pragma once
#include <optional>
#include <string>
#include <utility>

#include "io/metrics.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

// The die-filling metrics from a diagnostics.csv file (see above).
io::Metrics die_metrics(const std::string& diagnostics_csv, std::optional<std::pair<double, double>> front_impact);

// Reads DIR/diagnostics.csv (if `with_diagnostics`) and returns the metrics.
io::Metrics run_metrics(const std::string& dir, const DemSolver& dem, bool with_diagnostics,
                        std::optional<std::pair<double, double>> front_impact);
// The same from the totals (a run over MPI ranks: e = global energy, counts over the ranks).
io::Metrics run_metrics(const std::string& dir, double t, long particles, const EnergyBudget& e, long removed,
                        bool with_diagnostics, std::optional<std::pair<double, double>> front_impact);

}  // namespace cgdem::app
