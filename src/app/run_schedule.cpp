#include "app/run_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::app {

OutputSchedule::OutputSchedule(const DemCase& c, const DiagnosticsSpec& diag, double t_now, double largest_step)
    : t_start_(c.t_start),
      t_end_(c.t_end),
      tiny_(1e-9 * c.dem.dt),
      land_(1e-3 * c.dem.dt),
      energy_(c.output.energy_interval),
      snapshot_(c.output.snapshot_interval),
      checkpoint_(c.output.checkpoint_interval),
      diag_(diag.interval * std::max(1.0, std::ceil(std::max(largest_step, c.dem.dt) / diag.interval - 1e-9))),
      surface_(diag.surface_interval),
      largest_step_(std::max(largest_step, c.dem.dt)),
      with_diag_(diag.enabled),
      settled_pending_(t_now < -1e-9 * c.dem.dt) {
  next_energy_ = next_after(energy_, t_now);
  next_snap_ = next_after(snapshot_, t_now);
  next_checkpoint_ = next_after(checkpoint_, t_now);
  next_surface_ = next_after(surface_, t_now);
  // The first row time after t_now (the row at t_now is written before the loop).
  next_diag_ = static_cast<long>(std::floor((t_now - t_start_ + land_) / diag_)) + 1;
}

double OutputSchedule::next_after(double interval, double t) const {
  return t_start_ + interval * (std::floor((t - t_start_) / interval + 1e-9) + 1);
}

bool OutputSchedule::passes_diagnostics(double t0, double t1) const {
  if (!with_diag_) return false;
  const double tk = diag_time(next_diag_);
  return tk > t0 + land_ && tk < t1 - land_;
}

std::string OutputSchedule::diagnostics_note(double configured_interval) const {
  return fmt::format("rows: at t = {:.9g} s + k {:.9g} s (diagnostics.interval {:.9g} s{}); a step that passes a "
                     "row time without ending on it has that row interpolated linearly between its start and end "
                     "(counts from the nearer); the last row is the final state",
                     t_start_, diag_, configured_interval,
                     diag_ > configured_interval * (1 + 1e-9)
                         ? fmt::format(" rounded up to a multiple of at least the largest step {:.9g} s", largest_step_)
                         : "");
}

OutputSchedule::Due OutputSchedule::after_step(double t) {
  Due d;
  d.last = finished(t);
  d.snapshot = t >= next_snap_ - tiny_ || d.last;
  d.energy = t >= next_energy_ - tiny_ || d.snapshot;
  d.surface = with_diag_ && (t >= next_surface_ - tiny_ || d.last);
  d.checkpoint = t >= next_checkpoint_ - tiny_ || d.last;
  d.settled = settled_pending_ && t >= -tiny_;
  if (with_diag_) {
    while (diag_time(next_diag_) < t - land_) d.diagnostics_passed.push_back(diag_time(next_diag_++));
    if (std::fabs(diag_time(next_diag_) - t) <= land_) d.diagnostics = true, ++next_diag_;
    d.diagnostics = d.diagnostics || d.last;
  }
  auto advance = [&](bool due, double& next, double interval) {
    if (due)
      while (next <= t + tiny_) next += interval;
  };
  advance(d.energy, next_energy_, energy_);
  advance(d.surface, next_surface_, surface_);
  advance(d.snapshot, next_snap_, snapshot_);
  advance(d.checkpoint, next_checkpoint_, checkpoint_);
  if (d.settled) settled_pending_ = false;
  return d;
}

DiagnosticsRow interpolate_row(const DiagnosticsRow& a, const DiagnosticsRow& b, double t) {
  const double w = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 1.0;
  auto lerp = [w](double x, double y) { return (1 - w) * x + w * y; };
  const DiagnosticsRow& near = w < 0.5 ? a : b;
  DiagnosticsRow r = near;
  r.t = t;
  r.mass_in_die = lerp(a.mass_in_die, b.mass_in_die);
  r.transfer_rate = lerp(a.transfer_rate, b.transfer_rate);
  for (size_t c = 0; c < r.pressure.size() && c < a.pressure.size() && c < b.pressure.size(); ++c)
    r.pressure[c] = lerp(a.pressure[c], b.pressure[c]);
  r.mass_in_shoe = lerp(a.mass_in_shoe, b.mass_in_shoe);
  r.q_cavity = lerp(a.q_cavity, b.q_cavity), r.q_walls = lerp(a.q_walls, b.q_walls), r.q_open = lerp(a.q_open, b.q_open);
  r.v_bubbles = lerp(a.v_bubbles, b.v_bubbles), r.v_bubble_max = lerp(a.v_bubble_max, b.v_bubble_max);
  r.z_bubble = lerp(a.z_bubble, b.z_bubble), r.z_bubble_top = lerp(a.z_bubble_top, b.z_bubble_top);
  r.v_bubbles_shoe = lerp(a.v_bubbles_shoe, b.v_bubbles_shoe), r.v_sealed = lerp(a.v_sealed, b.v_sealed);
  return r;  // impacts and bubbles: the nearer row's
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

std::vector<std::string> csv_provenance(const std::string& comment) {
  return {fmt::format("cgdem {}, {}", kGitRevision, comment),
          "configuration: config.resolved.toml in this folder; units and columns: the lines below (SI units, the "
          "unit's suffix on every name, unit 1: dimensionless)"};
}

std::unique_ptr<io::CsvSeries> open_series(const std::string& dir, const std::string& name,
                                           const io::CsvColumns& columns, const std::string& comment, bool restart,
                                           double t, const std::vector<std::string>& notes) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  std::vector<std::string> provenance = csv_provenance(comment);
  provenance.insert(provenance.end(), notes.begin(), notes.end());
  return std::make_unique<io::CsvSeries>(path, columns, provenance, restart ? std::optional<double>(t) : std::nullopt);
}

void write_impacts(const std::string& dir, const DieDiagnostics& diag, const std::string& comment) {
  io::write_csv_file((std::filesystem::path(dir) / "impacts.csv").string(), DieDiagnostics::impact_columns(),
                     csv_provenance(comment), diag.impact_rows());
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

void count_drag_step(DragCounters& c, const CoupledStepStats& st) {
  if (st.drag.evaluations == 0) return;
  ++c.steps;
  c.iterations += st.drag.iterations;
  c.evaluations += st.drag.evaluations;
  c.max_iterations = std::max(c.max_iterations, st.drag.iterations);
  c.max_residual = std::max(c.max_residual, st.drag.residual);
}

void print_drag_counters(const DragCounters& c) {
  fmt::print("implicit drag: {} nonlinear solves, {:.2f} iterations and {:.2f} air steps per fluid step (at most {}), "
             "largest accepted residual {:.2e} m/s\n",
             c.steps, double(c.iterations) / c.steps, double(c.evaluations) / c.steps, c.max_iterations, c.max_residual);
}

const io::CsvColumns& air_steps_columns() {
  static const io::CsvColumns columns = {
      {"t_s", "s", "time at the end of the fluid step"},
      {"dt_fluid_s", "s", "length of the fluid step (its DEM substeps times the DEM step)"},
      {"pressure_iterations", "1",
       "Krylov iterations of the step's pressure solves (both Heun stages; implicit coupling: summed over every "
       "air step of the nonlinear solve), as the final report's mean counts them"},
      {"pressure_converged", "1", "1 when the pressure solves of the (accepted) air step converged, 0 when not"},
      {"pressure_residual", "1", "relative residual |r|/|b| of the last pressure solve of the (accepted) air step"},
      {"max_divergence_1_s", "1/s",
       "max |d(eps)/dt + div(eps u)| after the step over the cells with air (alpha_cell < 1)"},
      {"max_divergence_walls_1_s", "1/s",
       "the same over the cells entirely inside walls (not imposed there)"},
      {"drag_iterations", "1", "KINSOL's nonlinear iterations of the implicit drag coupling (0: no nonlinear solve)"},
      {"drag_evaluations", "1",
       "air steps of the implicit drag coupling's nonlinear solve, difference quotients included (0: none)"},
      {"drag_residual_m_s", "m/s", "max |G(u) - u| at the accepted iterate (nan: no nonlinear solve)"},
      {"drag_first_residual_m_s", "m/s", "max |G(u) - u| at the first evaluation, u = u^n (nan: no nonlinear solve)"}};
  return columns;
}

std::string air_steps_row(double t, const CoupledStepStats& st) {
  const fluid::StepStats& f = st.fluid;
  const ImplicitDragStats& d = st.drag;
  const double none = std::numeric_limits<double>::quiet_NaN();
  const bool solved = d.evaluations > 0;
  // t and dt in full (shortest exact form): the times are the sums of the steps.
  return fmt::format("{},{},{},{},{:.10g},{:.10g},{:.10g},{},{},{:.10g},{:.10g}", t, st.dt_fluid,
                     f.pressure_iterations, f.pressure_converged ? 1 : 0, f.pressure_residual, f.max_divergence,
                     f.max_divergence_walls, d.iterations, d.evaluations, solved ? d.residual : none,
                     solved ? d.first_residual : none);
}

const io::CsvColumns& timings_columns() {
  static const io::CsvColumns columns = {
      {"t_s", "s", "simulated time the run reached (its end, or where it stopped normally)"},
      {"t_start_s", "s", "simulated time the run started from (time.start, or the checkpoint's time of a --restart)"},
      {"revision", "1", "text: the git revision of the cgdem that ran it"},
      {"threads", "1", "OpenMP threads per process"},
      {"ranks", "1", "MPI ranks (the phase times are rank 0's)"},
      {"group", "1", "text: run (the whole), dem, coupling, air or output (the final report's per-phase tables)"},
      {"phase", "1", "text: the phase (run: wall, set_up, other); the report's name as an identifier"},
      {"seconds_s", "s", "wall-clock time spent in the phase during this run"},
      {"calls", "1", "times the phase was entered during this run (run rows: 1)"},
      {"dem_steps", "1", "DEM steps of this run"},
      {"fluid_steps", "1", "fluid steps of this run (0 without air)"},
      {"list_builds", "1", "neighbour-list builds of this run"},
      {"particles", "1", "parcels present at the end of this run"},
      {"peak_rss_MiB", "MiB", "peak resident memory of this run's process (the largest over the ranks)"},
  };
  return columns;
}

std::string phase_identifier(const std::string& name) {
  std::string id;
  bool gap = false;
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char ch = static_cast<unsigned char>(name[i]);
    if (name.compare(i, 2, "->") == 0) {
      id += id.empty() ? "to" : "_to";
      gap = true, ++i;
    } else if (std::isalnum(ch)) {
      if (gap && !id.empty()) id += '_';
      id += static_cast<char>(std::tolower(ch));
      gap = false;
    } else {
      gap = true;
    }
  }
  return id.empty() ? "unnamed" : id;
}

std::string timings_rows(const RunPiece& piece, const std::vector<std::pair<std::string, const PhaseTimers*>>& groups) {
  const std::string head = fmt::format("{:.10g},{:.10g},{},{},{}", piece.t_end, piece.t_start, kGitRevision,
                                       piece.threads, piece.ranks);
  const std::string tail = fmt::format("{},{},{},{},{:.1f}", piece.dem_steps, piece.fluid_steps, piece.list_builds,
                                       piece.particles, piece.peak_rss_mib);
  auto row = [&](const std::string& group, const std::string& phase, double seconds, long calls) {
    return fmt::format("{},{},{},{:.3f},{},{}\n", head, group, phase, seconds, calls, tail);
  };
  double in_groups = 0;
  std::string rows;
  for (const auto& [group, timers] : groups) {
    for (const PhaseTimers::Entry& e : timers->entries()) rows += row(group, phase_identifier(e.name), e.seconds, e.calls);
    in_groups += timers->total();
  }
  return row("run", "wall", piece.wall, 1) + row("run", "set_up", piece.set_up, 1) +
         row("run", "other", piece.wall - in_groups, 1) + rows;
}

void print_fluid_counters(const RunCounters& c) {
  fmt::print("fluid steps {}, mean pressure iterations per step {:.1f}, unconverged solves {}, max divergence "
             "{:.2e} 1/s in cells with air ({:.2e} 1/s inside walls, not imposed)\n",
             c.fluid_steps, c.fluid_steps ? double(c.pressure_iterations) / c.fluid_steps : 0.0, c.unconverged,
             c.max_divergence, c.max_divergence_walls);
}

}  // namespace cgdem::app
