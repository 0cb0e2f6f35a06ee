// Helpers shared by the DEM tests.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geometry/shape.hpp"
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

// A fixed floor z = 0 (solid below), one part.
inline geometry::Scene floor_scene() {
  geometry::Scene scene;
  const int b = scene.add_body("floor", geometry::Motion{});
  scene.add_part(b, "plane", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  return scene;
}

// Energy bookkeeping over many collisions (budget_test.cpp): three spinning parcels (l = 2)
// bounce on a floor and on each other for 30 ms with the contact law `model`; returns the
// largest closure error of E_kin + E_pot + E_el + dissipated, sampled every 0.1 ms, over
// the potential energy released.
inline double closure_error(double dt, const contact::ContactModel& model) {
  DemParams p;
  p.dt = dt;
  p.domain = {{-1, -1, -1}, {1, 1, 1}};
  DemSolver dem({powder(2)}, model, p, floor_scene());
  for (int k = 0; k < 3; ++k)
    dem.particles().add(k, 0, dem.species()[0], {0, 0.6e-4 * k, 0.4e-3 + 0.26e-3 * k}, {0.01 * k, 0, 0},
                        {0, 0, 100.0 * k});
  const EnergyBudget e0 = dem.energy();
  double worst = 0;
  for (int k = 1; k <= 300; ++k) {
    while (dem.time() < k * 1e-4 - 0.5 * dt) dem.step();
    worst = std::max(worst, std::fabs(dem.energy().balance() - e0.balance()));
  }
  return worst / (e0.potential - dem.energy().potential);
}

}  // namespace cgdem::test
