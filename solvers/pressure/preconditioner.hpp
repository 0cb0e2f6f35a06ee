// A preconditioner for the SPD form A = -div(a grad .) of poisson7.hpp: z ~= A^{-1} r.
// Implementations must be linear and symmetric (SUNDIALS PCG assumes a fixed SPD M).
#pragma once
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // Called after every change of coefficients; may be expensive (plans, factorisations).
  virtual void setup(const Poisson7& op) = 0;
  // z = M^{-1} r for arrays of length op.n().
  virtual void apply(const double* r, double* z) = 0;
};

}  // namespace cgdem::pressure
