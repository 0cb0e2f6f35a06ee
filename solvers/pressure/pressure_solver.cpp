// make_pressure_solver and the method registry behind it (pressure_solver.hpp).
#include "solvers/pressure/pressure_solver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "solvers/pressure/direct_solver.hpp"
#include "solvers/pressure/fft_preconditioner.hpp"
#include "solvers/pressure/krylov_solver.hpp"
#include "solvers/pressure/multigrid.hpp"

namespace cgdem::pressure {

namespace {

using Engine = KrylovSolver::Engine;
using Fft = FftPreconditioner;
using Mg = MultigridPreconditioner;

// Smoother relaxation of the W-cycle methods: 1.2 took the die-filling bench from 10.7 to 9.3
// iterations per fluid step (docs/pressure.md, "Cycle shape and coarse levels").
constexpr double kOmegaW = 1.2;

std::unique_ptr<PressureSolver> pcg_mg(const GridSpec& g, const SolverOptions& o, Engine e, int sweeps,
                                       Mg::Precision prec, Mg::Cycle cycle = Mg::Cycle::V, double omega = 1.0) {
  return std::make_unique<KrylovSolver>(g, o, std::make_unique<Mg>(g, sweeps, prec, cycle, omega), e);
}

// The method registry: name, one line of documentation, factory. Every reader of a method
// name (the case readers, `cgdem bench`, the error messages) takes the names from here.
struct MethodRow {
  PressureMethodInfo info;
  std::unique_ptr<PressureSolver> (*make)(const GridSpec&, const SolverOptions&, Engine);
};

const MethodRow kMethods[] = {
    {{"cg", "SUNDIALS PCG without preconditioner (the reference)"},
     [](const GridSpec& g, const SolverOptions& o, Engine) -> std::unique_ptr<PressureSolver> {
       return std::make_unique<KrylovSolver>(g, o, nullptr, Engine::Sundials);
     }},
    {{"pcg-fft", "PCG, preconditioned by the FFTW fast Poisson solve (diagonally scaled)"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) -> std::unique_ptr<PressureSolver> {
       return std::make_unique<KrylovSolver>(g, o, std::make_unique<Fft>(g, Fft::Scaling::Diagonal), e);
     }},
    {{"pcg-fft-plain", "PCG with the unscaled FFT preconditioner (kept for the benchmark comparison)"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) -> std::unique_ptr<PressureSolver> {
       return std::make_unique<KrylovSolver>(g, o, std::make_unique<Fft>(g, Fft::Scaling::None), e);
     }},
    {{"pcg-mg", "PCG, preconditioned by a geometric multigrid V-cycle (1 sweep, single precision, CHOLMOD coarsest)"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) { return pcg_mg(g, o, e, 1, Mg::Precision::Single); }},
    {{"pcg-mg2", "as pcg-mg with 2 smoothing sweeps per side (the die-filling cases' method)"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) { return pcg_mg(g, o, e, 2, Mg::Precision::Single); }},
    {{"pcg-mgw3", "PCG, preconditioned by a multigrid W-cycle (3 sweeps per side, over-relaxed by 1.2, single precision)"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) {
       return pcg_mg(g, o, e, 3, Mg::Precision::Single, Mg::Cycle::W, kOmegaW);
     }},
    {{"pcg-mg-f64", "as pcg-mg with the V-cycle in double precision"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) { return pcg_mg(g, o, e, 1, Mg::Precision::Double); }},
    {{"pcg-mg2-f64", "as pcg-mg2 with the V-cycle in double precision"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) { return pcg_mg(g, o, e, 2, Mg::Precision::Double); }},
    {{"pcg-mgw3-f64", "as pcg-mgw3 with the W-cycle in double precision"},
     [](const GridSpec& g, const SolverOptions& o, Engine e) {
       return pcg_mg(g, o, e, 3, Mg::Precision::Double, Mg::Cycle::W, kOmegaW);
     }},
    {{"cholmod", "sparse Cholesky factorisation of the whole operator (direct reference; slow, large)"},
     [](const GridSpec& g, const SolverOptions& o, Engine) -> std::unique_ptr<PressureSolver> {
       return std::make_unique<DirectSolver>(g, o);
     }},
};

}  // namespace

std::vector<PressureMethodInfo> pressure_methods() {
  std::vector<PressureMethodInfo> out;
  for (const auto& row : kMethods) out.push_back(row.info);
  return out;
}

std::vector<std::string> pressure_method_names() {
  std::vector<std::string> out;
  for (const auto& row : kMethods) out.emplace_back(row.info.name);
  return out;
}

std::unique_ptr<PressureSolver> make_pressure_solver(const GridSpec& grid, const SolverOptions& opt) {
  const MethodRow* row = nullptr;
  for (const auto& r : kMethods)
    if (opt.method == r.info.name) row = &r;
  if (!row)
    throw Error(fmt::format("pressure: unknown solver method '{}' (allowed: {})", opt.method,
                            fmt::join(pressure_method_names(), ", ")));
  if (opt.method == "cg" || opt.method == "cholmod") return row->make(grid, opt, Engine::Sundials);
  if (opt.krylov != "sundials" && opt.krylov != "fused")
    throw Error("pressure: unknown Krylov engine '" + opt.krylov + "' (known: sundials, fused)");
  Poisson7 check(grid);  // validates the grid before any planning
  return row->make(grid, opt, opt.krylov == "fused" ? Engine::Fused : Engine::Sundials);
}

}  // namespace cgdem::pressure
