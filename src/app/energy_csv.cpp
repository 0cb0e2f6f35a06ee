#include "app/energy_csv.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

namespace cgdem::app {

namespace {

// The columns that need the accounts.
bool needs_accounts(const std::string& column) {
  return column == "E_diss_damping_J" || column == "E_diss_friction_J" || column == "W_walls_J" ||
         column == "E_balance_J";
}

}  // namespace

io::CsvColumns energy_csv_columns(bool accounts) {
  io::CsvColumns columns = {
      {"t_s", "s", "time"},
      {"E_kin_trans_J", "J", "translational kinetic energy of the parcels, sum of m v^2 / 2"},
      {"E_kin_rot_J", "J", "rotational kinetic energy of the parcels, sum of I w^2 / 2 (in E_balance_J)"},
      {"E_kin_rot_orig_J", "J",
       "rotational kinetic energy of the l^3 originals each parcel stands for, E_kin_rot_J / l^2 (not in E_balance_J)"},
      {"E_pot_J", "J", "gravitational potential energy of the parcels, -sum of m g.x"},
      {"E_elastic_J", "J", "elastic energy stored in the contact springs (normal and tangential)"},
      {"E_diss_damping_J", "J", "energy dissipated by the normal contact dashpots since the start"},
      {"E_diss_friction_J", "J", "energy dissipated by the tangential dashpots and sliding since the start"},
      {"W_walls_J", "J", "work done on the parcels by moving walls since the start"},
      {"W_air_J", "J", "work done on the parcels by the air (drag and pressure force) since the start"},
      {"E_balance_J", "J",
       "budget closure E_kin_trans + E_kin_rot + E_pot + E_elastic + E_diss - W_walls - W_air (constant when closed)"},
      {"px_kg_m_s", "kg m/s", "total momentum of the parcels, x component"},
      {"py_kg_m_s", "kg m/s", "total momentum of the parcels, y component"},
      {"pz_kg_m_s", "kg m/s", "total momentum of the parcels, z component"},
      {"mass_kg", "kg", "solid mass of the parcels present"},
      {"particles", "1", "parcels present"},
      {"removed", "1", "parcels removed so far (left the domain)"},
      {"inside_walls", "1", "parcel centres inside a wall (tunnelled)"}};
  if (!accounts)
    for (io::CsvColumn& c : columns)
      if (needs_accounts(c.name))
        c.description = "NOT COMPUTED in this run (output.energy_accounts = false; every row holds nan): " +
                        c.description;
  return columns;
}

std::string energy_csv_accounts_note() {
  std::vector<std::string> names;
  for (const io::CsvColumn& c : energy_csv_columns())
    if (needs_accounts(c.name)) names.push_back(c.name);
  return fmt::format("output.energy_accounts = false: the contact energy accounts were not kept, so {} are not "
                     "computed (nan)",
                     fmt::join(names, ", "));
}

std::string energy_csv_row(double t, const EnergyBudget& e, long particles, long removed, long inside_walls) {
  return fmt::format("{:.9g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                     "{:.10g},{:.10g},{:.10g},{:.10g},{},{},{}",
                     t, e.kinetic_translational, e.kinetic_rotational, e.kinetic_rotational_originals,
                     e.potential, e.elastic, e.dissipated_damping, e.dissipated_friction, e.work_walls,
                     e.work_fluid, e.balance(), e.momentum.x, e.momentum.y, e.momentum.z, e.mass,
                     particles, removed, inside_walls);
}

}  // namespace cgdem::app
