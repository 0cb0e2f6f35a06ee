// PressureSolver for the Krylov methods ("cg", "pcg-fft", "pcg-mg"): PCG on the SPD system
// A phi = -rhs  (A = -div(a grad .), poisson7.hpp) with an optional preconditioner. Engine:
// SUNDIALS' SUNLinSol_PCG on serial N_Vectors (SolverOptions::krylov = "sundials", the
// default, and always for the unpreconditioned "cg" reference) or the fused PCG of
// fused_pcg.hpp ("fused", for comparison) - the same recurrence, so the same iterates up to
// rounding.
// Singular parts (floating components) are handled by projecting rhs, the preconditioned
// residual and phi onto the mean-free subspace of every floating component.
#pragma once
#include <memory>
#include <vector>

#include "solvers/pressure/fused_pcg.hpp"
#include "solvers/pressure/poisson7.hpp"
#include "solvers/pressure/preconditioner.hpp"
#include "solvers/pressure/pressure_solver.hpp"
#include "solvers/pressure/sundials_pcg.hpp"

namespace cgdem::pressure {

class KrylovSolver : public PressureSolver {
 public:
  enum class Engine { Fused, Sundials };
  // prec == nullptr: unpreconditioned CG.
  KrylovSolver(const GridSpec& g, const SolverOptions& opt, std::unique_ptr<Preconditioner> prec,
               Engine engine = Engine::Fused);
  void set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                        const std::vector<double>& az) override;
  SolveStats solve(const std::vector<double>& rhs, std::vector<double>& phi) override;
  void set_rel_tol(double rel_tol) override;
  const Poisson7& op() const { return op_; }

 private:
  SolverOptions opt_;
  Poisson7 op_;
  std::unique_ptr<Preconditioner> prec_;
  SundialsPcg pcg_;
  FusedPcg fused_;
  Engine engine_;
  bool have_coef_ = false;
  std::vector<double> b_, r_;
};

// Checks rhs/phi lengths against the grid (throws cgdem::Error).
void check_solve_args(const GridSpec& g, const std::vector<double>& rhs, const std::vector<double>& phi);

}  // namespace cgdem::pressure
