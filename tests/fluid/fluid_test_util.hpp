// Helpers shared by the air-phase verification tests: set fields from closed forms, norms,
// a time loop, and the CGDEM_FULL_VALIDATION switch.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "fluid/fluid_state.hpp"
#include "geometry/scene.hpp"
#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem::fluid::test {

using Fn = std::function<double(const Vec3&)>;

inline bool full_validation() {
  const char* e = std::getenv("CGDEM_FULL_VALIDATION");
  return e != nullptr && std::string(e) == "1";
}

// Sets the interior faces of component d (including the boundary faces) from fn(face centre).
inline void set_faces(const MacGrid& g, Field& f, int d, const Fn& fn) {
  for (int k = 0; k < f.nk(); ++k)
    for (int j = 0; j < f.nj(); ++j)
      for (int i = 0; i < f.ni(); ++i) f(i, j, k) = fn(g.face_centre(d, i, j, k));
}

inline void set_cells(const MacGrid& g, Field& f, const Fn& fn) {
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) f(i, j, k) = fn(g.cell_centre(i, j, k));
}

// Root-mean-square and max of (f - fn) over the faces of component d selected by `use`.
struct Norms {
  double rms = 0, max = 0;
  long n = 0;
};
inline Norms face_error(const MacGrid& g, const Field& f, int d, const Fn& fn,
                        const std::function<bool(const Vec3&)>& use = nullptr) {
  Norms r;
  double s2 = 0;
  for (int k = 0; k < f.nk(); ++k)
    for (int j = 0; j < f.nj(); ++j)
      for (int i = 0; i < f.ni(); ++i) {
        Vec3 x = g.face_centre(d, i, j, k);
        if (use && !use(x)) continue;
        double e = f(i, j, k) - fn(x);
        s2 += e * e;
        r.max = std::max(r.max, std::fabs(e));
        ++r.n;
      }
  r.rms = r.n ? std::sqrt(s2 / r.n) : 0;
  return r;
}

// Kinetic energy per unit depth (2-D slab): 1/2 sum over faces of u^2 dx^2 (periodic grids:
// faces 0..n-1 only).
inline double kinetic_energy_2d(const FluidState& s) {
  const MacGrid& g = s.grid;
  double e = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) e += s.u(i, j, 0) * s.u(i, j, 0) + s.v(i, j, 0) * s.v(i, j, 0);
  return 0.5 * e * g.dx * g.dx;
}

// Observed order from errors on grids refined by 2.
inline double order(double e_coarse, double e_fine) { return std::log(e_coarse / e_fine) / std::log(2.0); }

// Advances to t_end with the stable step (the last one shortened); calls each(stats) after
// every step. Returns the number of steps.
inline int run_to(FluidSolver& solver, FluidState& s, const geometry::Scene& scene, double t_end,
                  const std::function<void(const StepStats&)>& each = nullptr, const Sources& src = {}) {
  int steps = 0;
  while (s.t < t_end - 1e-12 * t_end) {
    double dt = std::min(solver.stable_dt(s), t_end - s.t);
    StepStats st = solver.advance(s, scene.at(s.t + dt), src, dt);
    if (each) each(st);
    ++steps;
  }
  return steps;
}

}  // namespace cgdem::fluid::test
