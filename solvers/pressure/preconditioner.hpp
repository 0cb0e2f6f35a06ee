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
  // True when apply() writes z = 0 on every cell outside op.active()'s segments (cells with
  // D = 0, which the projection onto the floating components would set to 0 anyway).
  virtual bool zero_outside_active() const { return false; }
};

}  // namespace cgdem::pressure
