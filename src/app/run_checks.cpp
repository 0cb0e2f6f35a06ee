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

}  // namespace cgdem::app
