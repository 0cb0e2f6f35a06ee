// energy.csv: the particle energy and momentum budget as a time series, one row per
// output.energy_interval. The columns (name with SI unit, unit, description) and the row are
// defined together here so that they cannot drift apart; the file's layout is that of
// io/csv_series.hpp, and readers (scaling/) look columns up by name, never by position.
// E_kin_rot_J is the parcels' own 1/2 I w^2 (in E_balance_J); E_kin_rot_orig_J that of the
// l^3 originals each parcel stands for, smaller by l^2 (eq. 5; EnergyBudget).
#pragma once
#include <string>

#include "io/csv_series.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

// t_s, E_kin_trans_J, ..., particles, removed, inside_walls. Without the contact energy
// accounts (output.energy_accounts = false) the columns they feed say that they were not
// computed (their rows hold nan).
io::CsvColumns energy_csv_columns(bool accounts = true);
// The header line of an energy.csv written without the accounts: the columns it did not compute.
std::string energy_csv_accounts_note();

// One row (no trailing newline) of the totals over the ranks (one process: its own).
// `e` must already carry work_fluid (DemSolver::fluid_work()).
std::string energy_csv_row(double t, const EnergyBudget& e, long particles, long removed, long inside_walls);

}  // namespace cgdem::app
