// make_pressure_solver: the method registry of pressure_solver.hpp.
#include "solvers/pressure/pressure_solver.hpp"

#include "core/error.hpp"
#include "solvers/pressure/direct_solver.hpp"
#include "solvers/pressure/fft_preconditioner.hpp"
#include "solvers/pressure/krylov_solver.hpp"
#include "solvers/pressure/multigrid.hpp"

namespace cgdem::pressure {

std::unique_ptr<PressureSolver> make_pressure_solver(const GridSpec& grid, const SolverOptions& opt) {
  if (opt.method == "cg")  // the reference: SUNDIALS' PCG without preconditioner
    return std::make_unique<KrylovSolver>(grid, opt, nullptr, KrylovSolver::Engine::Sundials);
  if (opt.method == "cholmod") return std::make_unique<DirectSolver>(grid, opt);
  if (opt.krylov != "sundials" && opt.krylov != "fused")
    throw Error("pressure: unknown Krylov engine '" + opt.krylov + "' (known: sundials, fused)");
  const auto engine = opt.krylov == "fused" ? KrylovSolver::Engine::Fused : KrylovSolver::Engine::Sundials;
  Poisson7 check(grid);  // validates the grid before any planning
  using Fft = FftPreconditioner;
  if (opt.method == "pcg-fft")
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<Fft>(grid, Fft::Scaling::Diagonal), engine);
  using Mg = MultigridPreconditioner;
  // pcg-mg2: two smoothing sweeps per side; the -f64 variants run the V-cycle in double.
  if (opt.method == "pcg-mg" || opt.method == "pcg-mg2" || opt.method == "pcg-mg-f64" ||
      opt.method == "pcg-mg2-f64") {
    const int nu = opt.method.rfind("pcg-mg2", 0) == 0 ? 2 : 1;
    const auto prec = opt.method.ends_with("-f64") ? Mg::Precision::Double : Mg::Precision::Single;
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<Mg>(grid, nu, prec), engine);
  }
  if (opt.method == "pcg-fft-plain")  // unscaled variant, kept for the benchmark comparison
    return std::make_unique<KrylovSolver>(grid, opt, std::make_unique<Fft>(grid, Fft::Scaling::None), engine);
  throw Error("pressure: unknown solver method '" + opt.method +
              "' (known: cg, pcg-fft, pcg-fft-plain, pcg-mg, pcg-mg2, pcg-mg-f64, pcg-mg2-f64, cholmod)");
}

}  // namespace cgdem::pressure
