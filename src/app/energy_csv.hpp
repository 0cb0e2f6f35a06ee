// energy.csv: the particle energy and momentum budget as a time series, one row per
// output.energy_interval. Header and row are defined together here so that columns cannot
// drift apart; readers (scaling/) look columns up by name, never by position.
#pragma once
#include <string>

#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

// Column names, comma-separated (no trailing newline).
std::string energy_csv_header();

// One row (no trailing newline). `e` must already carry work_fluid (DemSolver::fluid_work()).
std::string energy_csv_row(const DemSolver& dem, const EnergyBudget& e, long inside_walls);

}  // namespace cgdem::app
