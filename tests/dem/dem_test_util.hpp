// Helpers shared by the DEM tests.
#pragma once
#include <cmath>
#include <cstdio>

#include "solvers/dem/dem_solver.hpp"

namespace cgdem::test {

inline Species powder(double ratio, double d_original = 125e-6) { return {"powder", d_original, ratio, 1500.0}; }

inline DemParams no_gravity(double dt) {
  DemParams p;
  p.dt = dt;
  p.gravity = {0, 0, 0};
  p.domain = {{-1, -1, -1}, {1, 1, 1}};
  return p;
}

inline double rel_err(double got, double want) { return std::fabs(got - want) / std::fabs(want); }

}  // namespace cgdem::test
