// The FluidSolver constructor that builds its own pressure solver (kept in its own file so
// that a caller injecting a pressure solver does not link make_pressure_solver).
#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem::fluid {

FluidSolver::FluidSolver(const MacGrid& g, FluidParams params)
    : FluidSolver(g, params, pressure::make_pressure_solver(pressure_grid(g, params), params.pressure)) {}

}  // namespace cgdem::fluid
