// make_pressure_solver: the method registry of pressure_solver.hpp.
#include "solvers/pressure/pressure_solver.hpp"

#include "core/error.hpp"
#include "solvers/pressure/direct_solver.hpp"
#include "solvers/pressure/fft_preconditioner.hpp"
#include "solvers/pressure/krylov_solver.hpp"
#include "solvers/pressure/multigrid.hpp"

namespace cgdem::pressure {

std::unique_ptr<PressureSolver> make_pressure_solver(const GridSpec& grid, const SolverOptions& opt) {
  if (opt.method == "cg") return std::make_unique<KrylovSolver>(grid, opt, nullptr);
  if (opt.method == "cholmod") return std::make_unique<DirectSolver>(grid, opt);
  Poisson7 check(grid);  // validates the grid before any planning
  using Fft = FftPreconditioner;
  if (opt.method == "pcg-fft")
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<Fft>(grid, Fft::Scaling::Diagonal));
  if (opt.method == "pcg-mg")
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<MultigridPreconditioner>(grid, 1));
  if (opt.method == "pcg-mg2")  // two smoothing sweeps per side, kept for the benchmark comparison
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<MultigridPreconditioner>(grid, 2));
  if (opt.method == "pcg-fft-plain")  // unscaled variant, kept for the benchmark comparison
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<Fft>(grid, Fft::Scaling::None));
  throw Error("pressure: unknown solver method '" + opt.method +
              "' (known: cg, pcg-fft, pcg-mg, cholmod)");
}

}  // namespace cgdem::pressure
