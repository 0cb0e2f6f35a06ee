// energy.csv: the particle energy and momentum budget as a time series, one row per
// output.energy_interval. Header and row are defined together here so that columns cannot
// drift apart; readers (scaling/) look columns up by name, never by position.
// E_kin_rot is the parcels' own 1/2 I w^2 (in E_balance); E_kin_rot_orig that of the l^3
// originals each parcel stands for, smaller by l^2 (eq. 5; EnergyBudget). Energies in J,
// momentum in kg m/s, mass in kg.
#pragma once
#include <string>

#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

// Column names, comma-separated (no trailing newline).
std::string energy_csv_header();

// One row (no trailing newline). `e` must already carry work_fluid (DemSolver::fluid_work()).
std::string energy_csv_row(const DemSolver& dem, const EnergyBudget& e, long inside_walls);
// The same row from its values (a run over MPI ranks: totals over the ranks).
std::string energy_csv_row(double t, const EnergyBudget& e, long particles, long removed, long inside_walls);

}  // namespace cgdem::app
