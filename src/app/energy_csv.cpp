#include "app/energy_csv.hpp"

#include <fmt/format.h>

namespace cgdem::app {

std::string energy_csv_header() {
  return "t,E_kin_trans,E_kin_rot,E_kin_rot_orig,E_pot,E_elastic,E_diss_damping,E_diss_friction,W_walls,W_air,"
         "E_balance,px,py,pz,mass,particles,removed,inside_walls";
}

std::string energy_csv_row(const DemSolver& dem, const EnergyBudget& e, long inside_walls) {
  return energy_csv_row(dem.time(), e, static_cast<long>(dem.particles().size()), dem.removed(), inside_walls);
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
