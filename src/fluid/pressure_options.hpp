// The options of the air's pressure solve, as the air step (fluid/fluid_state.hpp's
// FluidParams) carries them and the pressure solvers (solvers/pressure) read them. A
// building block of its own so that the air's parameters do not depend on the solvers.
#pragma once
#include <string>

namespace cgdem::pressure {

struct SolverOptions {
  // The method, one of make_pressure_solver's (solvers/pressure/pressure_solver.cpp):
  // "cg" (unpreconditioned SUNDIALS PCG, the reference), "pcg-fft" (PCG with the FFTW fast
  // Poisson solve as preconditioner; this struct's default), "pcg-mg" / "pcg-mg2" (PCG with
  // geometric multigrid, one or two smoothing sweeps, CHOLMOD on the coarsest level;
  // "pcg-mg2" is what the case files use), their "-f64" variants (V-cycle in double),
  // "pcg-fft-plain" (unscaled FFT, for the benchmark) and "cholmod" (direct reference).
  std::string method = "pcg-fft";
  // The Krylov engine of the preconditioned methods: "sundials" (SUNDIALS' PCG, the
  // default) or "fused" (the same recurrence in four memory passes per iteration,
  // fused_pcg.hpp; same iterates to ~1e-13). "cg" always runs on SUNDIALS.
  std::string krylov = "sundials";
  double rel_tol = 1e-8;   // ||r|| <= rel_tol ||b||
  int max_iter = 500;
};

}  // namespace cgdem::pressure
