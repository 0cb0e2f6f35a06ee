#include "scaling/observables.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/error.hpp"
#include "io/metrics.hpp"
#include "io/particle_h5.hpp"
#include "scaling/csv_table.hpp"
#include "scaling/fields.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

void pile_observables(const std::vector<Vec3>& x, const std::vector<double>& d, const ProfileSpec& s,
                      RunObservables& out) {
  if (!(s.bin > 0)) throw Error("pile profile: the column width must be positive");
  const int nx = std::max(1, static_cast<int>(std::ceil((s.x_hi - s.x_lo) / s.bin - 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::floor((s.y_hi - s.y_lo) / s.bin + 1e-9)));
  std::vector<double> top(static_cast<size_t>(nx) * ny, -INFINITY);
  double V = 0, Vx = 0, Vy = 0, Vz = 0;
  std::vector<std::pair<double, double>> xv;  // (x, volume) for the run-out
  for (size_t p = 0; p < x.size(); ++p) {
    const double v = std::numbers::pi * d[p] * d[p] * d[p] / 6;
    V += v, Vx += v * (x[p].x - s.x_lo), Vy += v * (x[p].y - s.y_lo), Vz += v * (x[p].z - s.z_lo);
    xv.push_back({x[p].x - s.x_lo, v});
    const int i = std::clamp(static_cast<int>(std::floor((x[p].x - s.x_lo) / s.bin)), 0, nx - 1);
    const int j = std::clamp(static_cast<int>(std::floor((x[p].y - s.y_lo) / (s.y_hi - s.y_lo) * ny)), 0, ny - 1);
    double& t = top[static_cast<size_t>(i) * ny + j];
    t = std::max(t, x[p].z + 0.5 * d[p] - s.z_lo);
  }
  out.profile_x.assign(nx, 0);
  out.profile_h.assign(nx, 0);
  for (int i = 0; i < nx; ++i) {
    out.profile_x[i] = s.x_lo + (i + 0.5) * s.bin;
    double sum = 0;
    int n = 0;
    for (int j = 0; j < ny; ++j)
      if (std::isfinite(top[static_cast<size_t>(i) * ny + j])) sum += top[static_cast<size_t>(i) * ny + j], ++n;
    out.profile_h[i] = n ? sum / n : 0.0;
  }
  if (V > 0) {
    std::sort(xv.begin(), xv.end());
    double acc = 0, x95 = xv.back().first;
    for (const auto& [px, v] : xv)
      if ((acc += v) >= 0.95 * V) {
        x95 = px;
        break;
      }
    out.scalars["runout_x95_m"] = x95;
    out.scalars["com_x_m"] = Vx / V;
    out.scalars["com_y_m"] = Vy / V;
    out.scalars["com_z_m"] = Vz / V;
    out.scalars["pile_top_m"] = *std::max_element(out.profile_h.begin(), out.profile_h.end());
  }
}

RunObservables read_observables(const std::string& dir, const ProfileSpec& s, double t0) {
  RunObservables o;
  const fs::path d(dir);
  if (fs::exists(d / "diagnostics.csv")) {
    const CsvTable c = read_csv_table((d / "diagnostics.csv").string());
    // Rows from t0 on.
    size_t first = 0;
    const auto& t_all = c.col("t_s");
    while (first < t_all.size() && t_all[first] < t0 - 1e-9 * std::fabs(t_all.back() - t_all.front())) ++first;
    auto from_t0 = [&](const std::string& n) {
      const auto& v = c.col(n);
      return std::vector<double>(v.begin() + static_cast<long>(first), v.end());
    };
    const std::vector<double> t = from_t0("t_s");
    if (!t.empty()) {
      o.transfer_rate = {t, from_t0("transfer_rate_kg_s")};
      const Peak pk = peak(o.transfer_rate);
      o.scalars["transfer_rate_peak_kg_s"] = pk.value;
      o.scalars["transfer_rate_peak_time_s"] = pk.t;
      o.scalars["fill_mass_kg"] = c.col("mass_in_die_kg").back();
      for (size_t k = 0; k < c.names.size(); ++k)
        if (const std::string n = c.quantity(k); n.rfind("p_", 0) == 0) {  // p_A_Pa -> p_A
          o.pressure[n] = {t, from_t0(c.names[k])};
          const Peak pp = peak(o.pressure[n]);
          o.scalars[n + "_peak_Pa"] = pp.value;
          o.scalars[n + "_peak_time_s"] = pp.t;
        }
    }
  }
  if (fs::exists(d / "metrics.csv")) {  // the run's own figures take precedence
    // metrics.csv takes the pressure peaks over the filling window and leaves them out where
    // they cannot be computed (no air; src/app/run_metrics.hpp): the whole-series peaks found
    // above give way to its figures, or to nothing.
    std::erase_if(o.scalars, [](const auto& kv) { return kv.first.rfind("p_", 0) == 0; });
    for (const auto& [n, v] : io::read_metrics((d / "metrics.csv").string())) o.scalars[n] = v;
  }
  const auto frames = list_frames(dir, "particles");
  if (frames.empty()) throw Error(fmt::format("{}: no particle snapshots (particles_*.h5)", dir));
  const io::ParticleTable t = io::read_particles_h5(frames.back().file);
  o.final_time = frames.back().t;
  pile_observables(t.x, t.d, s, o);
  return o;
}

}  // namespace cgdem::scaling
