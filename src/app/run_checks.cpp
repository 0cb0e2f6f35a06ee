#include "app/run_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace cgdem::app {

void check_particles(const Particles& p, size_t n, long step, double t, double max_speed) {
  n = std::min(n, p.size());
  for (size_t i = 0; i < n; ++i) {
    const Vec3 &x = p.x[i], &v = p.v[i];
    const bool finite = std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(v.x) &&
                        std::isfinite(v.y) && std::isfinite(v.z);
    if (!finite || norm(v) > max_speed)
      throw RunError(fmt::format(
          "step {}, t = {:.6g} s: particle id {} has {} (x = [{:.4g}, {:.4g}, {:.4g}] m, |v| = {:.4g} m/s; "
          "output.max_speed = {:g}). The run stopped; the last good state is last_good.h5 in the output folder "
          "(checkpoint.bin continues from there with --restart).",
          step, t, p.id[i], finite ? "a runaway velocity" : "a non-finite position or velocity", x.x, x.y, x.z,
          norm(v), max_speed));
  }
}

long count_inside_walls(const geometry::Scene& scene, double t, const Particles& p, size_t n) {
  if (scene.empty()) return 0;
  const auto frame = scene.at(t);
  n = std::min(n, p.size());
  long inside = 0;
  for (size_t i = 0; i < n; ++i)
    if (frame.phi(p.x[i]) < 0) ++inside;
  return inside;
}

void check_air(const fluid::FluidState& air, double max_speed, long step, std::array<int, 3> first_cell) {
  const auto& g = air.grid;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double u = air.u(i, j, k), v = air.v(i, j, k), w = air.w(i, j, k), p = air.p(i, j, k);
        const char* what = nullptr;
        if (!std::isfinite(p)) what = "a non-finite pressure";
        else if (!(std::fabs(u) <= max_speed && std::fabs(v) <= max_speed && std::fabs(w) <= max_speed))
          what = "a non-finite or runaway air velocity";
        if (!what) continue;
        const Vec3 x = g.cell_centre(i, j, k);
        throw RunError(fmt::format(
            "fluid step {}, t = {:.6g} s: cell ({}, {}, {}) at [{:.4g}, {:.4g}, {:.4g}] m has {} (u = [{:.4g}, {:.4g}, "
            "{:.4g}] m/s, p = {:.4g} Pa; output.max_speed = {:g}). The run stopped; the last good state is "
            "last_good.h5 in the output folder (checkpoint.bin continues from there with --restart).",
            step, air.t, i + first_cell[0], j + first_cell[1], k + first_cell[2], x.x, x.y, x.z, what, u, v, w, p,
            max_speed));
      }
}

}  // namespace cgdem::app
