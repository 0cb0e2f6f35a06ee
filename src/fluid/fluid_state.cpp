#include "fluid/fluid_state.hpp"

#include <fmt/format.h>

namespace cgdem::fluid {

FluidState make_fluid_state(const MacGrid& g) {
  g.validate();
  FluidState s;
  s.grid = g;
  s.u = make_face_field(g, 0);
  s.v = make_face_field(g, 1);
  s.w = make_face_field(g, 2);
  s.p = make_cell_field(g);
  s.eps = make_cell_field(g, 1.0);
  s.eps_old = make_cell_field(g, 1.0);
  return s;
}

void FluidParams::validate() const {
  if (!(rho > 0)) throw Error(fmt::format("fluid: rho must be > 0 (got {} kg/m^3)", rho));
  if (!(mu >= 0)) throw Error(fmt::format("fluid: mu must be >= 0 (got {} Pa s)", mu));
  if (time_order != 1 && time_order != 2) throw Error(fmt::format("fluid: time_order must be 1 or 2 (got {})", time_order));
  if (!(stage_rel_tol >= 0 && stage_rel_tol < 1))
    throw Error(fmt::format("fluid: stage_rel_tol must be in [0, 1) (got {})", stage_rel_tol));
  if (ibm_samples < 1) throw Error("fluid: ibm_samples must be >= 1");
  if (!(cfl > 0 && cfl <= 1)) throw Error(fmt::format("fluid: cfl must be in (0, 1] (got {})", cfl));
  if (!(visc_safety > 0 && visc_safety <= 1))
    throw Error(fmt::format("fluid: visc_safety must be in (0, 1] (got {})", visc_safety));
  if (!(dt_max > 0)) throw Error("fluid: dt_max must be > 0");
  validate_boundary(bc);
}

}  // namespace cgdem::fluid
