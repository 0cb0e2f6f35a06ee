#include "app/run_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/checkpoint.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::app {

OutputSchedule::OutputSchedule(const DemCase& c, const DiagnosticsSpec& diag, double t_now)
    : t_start_(c.t_start),
      t_end_(c.t_end),
      tiny_(1e-9 * c.dem.dt),
      energy_(c.output.energy_interval),
      snapshot_(c.output.snapshot_interval),
      checkpoint_(c.output.checkpoint_interval),
      diag_(diag.interval),
      surface_(diag.surface_interval),
      with_diag_(diag.enabled),
      settled_pending_(t_now < -1e-9 * c.dem.dt) {
  next_energy_ = next_after(energy_, t_now);
  next_snap_ = next_after(snapshot_, t_now);
  next_checkpoint_ = next_after(checkpoint_, t_now);
  next_diag_ = next_after(diag_, t_now);
  next_surface_ = next_after(surface_, t_now);
}

double OutputSchedule::next_after(double interval, double t) const {
  return t_start_ + interval * (std::floor((t - t_start_) / interval + 1e-9) + 1);
}

OutputSchedule::Due OutputSchedule::after_step(double t) {
  Due d;
  d.last = finished(t);
  d.snapshot = t >= next_snap_ - tiny_ || d.last;
  d.energy = t >= next_energy_ - tiny_ || d.snapshot;
  d.diagnostics = with_diag_ && (t >= next_diag_ - tiny_ || d.last);
  d.surface = with_diag_ && (t >= next_surface_ - tiny_ || d.last);
  d.checkpoint = t >= next_checkpoint_ - tiny_ || d.last;
  d.settled = settled_pending_ && t >= -tiny_;
  auto advance = [&](bool due, double& next, double interval) {
    if (due)
      while (next <= t + tiny_) next += interval;
  };
  advance(d.energy, next_energy_, energy_);
  advance(d.diagnostics, next_diag_, diag_);
  advance(d.surface, next_surface_, surface_);
  advance(d.snapshot, next_snap_, snapshot_);
  advance(d.checkpoint, next_checkpoint_, checkpoint_);
  if (d.settled) settled_pending_ = false;
  return d;
}

ProgressLine::ProgressLine(const DemCase& c, double t_first, bool tty)
    : t_start_(c.t_start), t_end_(c.t_end), t_first_(t_first), interval_(c.output.progress_interval), tty_(tty) {}

void ProgressLine::update(double t, long particle_steps, bool last) {
  const double wall = clock_.seconds();
  if (!((tty_ && wall - last_ > 0.5) || (!tty_ && wall - last_ > interval_) || last)) return;
  last_ = wall;
  const double frac = (t - t_start_) / (t_end_ - t_start_), rate = particle_steps / std::max(wall, 1e-9);
  const double done = (t - t_first_) / std::max(t_end_ - t_first_, 1e-300);
  const std::string line = fmt::format("t = {:.5f} s  {:5.1f}%  {:.3g} particle-steps/s  ETA {:.0f} s", t,
                                       100 * frac, rate, wall * (1 - done) / std::max(done, 1e-9));
  if (tty_) fmt::print("\r{}   ", line), std::fflush(stdout);
  else fmt::print("{}\n", line), std::fflush(stdout);  // batch logs see progress as it happens
}

void ProgressLine::finish() const {
  if (tty_) fmt::print("\n");
}

std::FILE* open_series(const std::string& dir, const std::string& name, const std::string& header,
                       const std::string& comment, bool restart, double t) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  if (restart && std::filesystem::exists(path)) {
    truncate_csv_after(path, t);
    std::FILE* f = std::fopen(path.c_str(), "a");
    if (!f) throw Error("cannot append to " + path);
    return f;
  }
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw Error("cannot write " + path);
  std::fprintf(f, "# cgdem %s, %s\n%s\n", kGitRevision, comment.c_str(), header.c_str());
  return f;
}

void write_impacts(const std::string& dir, const DieDiagnostics& diag) {
  std::string rows = "id,t,speed_down,mass\n";
  for (const auto& im : diag.impacts())
    rows += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", im.id, im.t, im.speed_down, im.mass);
  io::write_file_atomic((std::filesystem::path(dir) / "impacts.csv").string(), rows);
}

void print_front(const DieDiagnostics& diag, const DiagnosticsSpec& spec) {
  const auto front = diag.front_impact();
  if (front)
    fmt::print("powder front reached the die floor at t = {:.4f} s; mean impact velocity {:.3f} m/s (first {:g} s)\n",
               front->first, front->second, spec.impact_window);
  else
    fmt::print("the powder has not reached the die floor yet\n");
}

void write_air_snapshot(io::GridSnapshotSeries& series, long step, const fluid::FluidState& air,
                        const fluid::Field& alpha) {
  const auto& g = air.grid;
  const size_t n = static_cast<size_t>(g.cells());
  io::CellScalars s{{"eps", std::vector<double>(n)}, {"p", std::vector<double>(n)}, {"alpha", std::vector<double>(n)}};
  io::CellVectors v{{"u", {std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)}}};
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t c = static_cast<size_t>(i + g.nx * (j + static_cast<long>(g.ny) * k));
        s["eps"][c] = air.eps(i, j, k);
        s["p"][c] = air.p(i, j, k);
        s["alpha"][c] = alpha.empty() ? 0.0 : alpha(i, j, k);
        v["u"][0][c] = 0.5 * (air.u(i, j, k) + air.u(i + 1, j, k));
        v["u"][1][c] = 0.5 * (air.v(i, j, k) + air.v(i, j + 1, k));
        v["u"][2][c] = 0.5 * (air.w(i, j, k) + air.w(i, j, k + 1));
      }
  series.write(step, air.t, g.nx, g.ny, g.nz, g.origin, Vec3{g.dx, g.dx, g.dx}, s, v);
}

void count_fluid_step(RunCounters& c, const CoupledStepStats& st, double t, bool announce) {
  ++c.fluid_steps;
  c.pressure_iterations += st.fluid.pressure_iterations;
  c.max_divergence = std::max(c.max_divergence, st.fluid.max_divergence);
  c.max_divergence_walls = std::max(c.max_divergence_walls, st.fluid.max_divergence_walls);
  if (!st.fluid.pressure_converged && c.unconverged++ == 0 && announce)
    fmt::print(stderr, "cgdem: warning: t = {:.6g} s: pressure solve not converged (residual {:.2e}); "
               "counted in the final report\n", t, st.fluid.pressure_residual);
}

void print_fluid_counters(const RunCounters& c) {
  fmt::print("fluid steps {}, mean pressure iterations per step {:.1f}, unconverged solves {}, max divergence "
             "{:.2e} 1/s in cells with air ({:.2e} 1/s inside walls, not imposed)\n",
             c.fluid_steps, c.fluid_steps ? double(c.pressure_iterations) / c.fluid_steps : 0.0, c.unconverged,
             c.max_divergence, c.max_divergence_walls);
}

}  // namespace cgdem::app
