// The options of the air's pressure solve, as the air step (fluid/fluid_state.hpp's
// FluidParams) carries them and the pressure solvers (solvers/pressure) read them. A
// building block of its own so that the air's parameters do not depend on the solvers.
#pragma once
#include <string>

namespace cgdem::pressure {

struct SolverOptions {
  // The method: a name of the registry behind make_pressure_solver (pressure_methods() in
  // solvers/pressure/pressure_solver.hpp lists them with a line each). "pcg-fft" is this
  // struct's default; the case files use "pcg-mg2".
  std::string method = "pcg-fft";
  // The Krylov engine of the preconditioned methods: "sundials" (SUNDIALS' PCG, the
  // default) or "fused" (the same recurrence in four memory passes per iteration,
  // fused_pcg.hpp; same iterates to ~1e-13). "cg" always runs on SUNDIALS.
  std::string krylov = "sundials";
  double rel_tol = 1e-8;   // ||r|| <= rel_tol ||b||
  int max_iter = 500;
};

}  // namespace cgdem::pressure
