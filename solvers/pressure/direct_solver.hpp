// PressureSolver "cholmod": direct sparse Cholesky of A phi = -rhs (cholmod_factor.hpp); the
// factorisation happens in set_coefficients, solve() is two triangular solves. Reports
// iterations = 1 and the true relative residual (converged if it is <= opt.rel_tol).
#pragma once
#include <memory>
#include <vector>

#include "solvers/pressure/cholmod_factor.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::pressure {

class DirectSolver : public PressureSolver {
 public:
  DirectSolver(const GridSpec& g, const SolverOptions& opt) : opt_(opt), op_(g) {}
  void set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                        const std::vector<double>& az) override;
  SolveStats solve(const std::vector<double>& rhs, std::vector<double>& phi) override;
  void set_rel_tol(double rel_tol) override;

 private:
  SolverOptions opt_;
  Poisson7 op_;
  std::unique_ptr<CholmodFactor> factor_;
  std::vector<double> b_, r_;
};

}  // namespace cgdem::pressure
