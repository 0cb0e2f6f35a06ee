#include "app/run_case.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "app/checkpoint.hpp"
#include "app/run_checks.hpp"
#include "app/energy_csv.hpp"
#include "app/run_metrics.hpp"
#include "app/run_schedule.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "particles/particle_io.hpp"

namespace cgdem::app {

namespace {

// The health checks of the DEM (run_checks.hpp) over all its particles.
void check_particles(const DemSolver& dem, double max_speed) {
  app::check_particles(dem.particles(), dem.particles().size(), dem.steps(), dem.time(), max_speed);
}

// Particles whose centre lies inside a wall (tunnelled): counted, not hidden.
long count_inside_walls(const DemSolver& dem) {
  return app::count_inside_walls(dem.scene(), dem.time(), dem.particles(), dem.particles().size());
}

}  // namespace

int run_case(const DemCase& c, const AirCase& air_case, const DiagnosticsSpec& diag_spec, const RunInfo& info) {
  namespace fs = std::filesystem;
  fs::create_directories(c.output.dir);
  const fs::path out(c.output.dir);
  const std::string case_dir = fs::path(info.case_file).parent_path().string();
  io::write_file_atomic((out / "config.resolved.toml").string(),
                        fmt::format("# cgdem {} resolved configuration of {}\n{}", kGitRevision, info.case_file,
                                    info.resolved_config));
  io::Attributes attrs{{"cgdem_revision", kGitRevision}, {"config", info.resolved_config}};

  Stopwatch setup_clock;
  auto dem = build_solver(c, case_dir.empty() ? "." : case_dir);
  const bool with_air = air_case.enabled;
  fluid::FluidState air;
  std::unique_ptr<fluid::FluidSolver> fluid;
  std::unique_ptr<CoupledSolver> coupled;
  if (with_air) {
    air = fluid::make_fluid_state(air_case.grid);
    fluid = std::make_unique<fluid::FluidSolver>(air_case.grid, air_case.fluid);
    coupled = std::make_unique<CoupledSolver>(*dem, *fluid, air,
                                              coupling::Exchange(air_case.grid, c.species, air_case.exchange),
                                              air_case.coupled);
  }
  std::vector<double> sp_mass, sp_d;
  for (const auto& s : c.species) sp_mass.push_back(s.mass()), sp_d.push_back(s.diameter());
  DieDiagnostics diag(diag_spec, sp_mass, sp_d);
  RunCounters counters;
  DragCounters drag_counters;  // implicit drag coupling, since this process started (not checkpointed)
  const bool restart = !info.restart.empty();
  if (restart) {
    const std::string stored = read_checkpoint(info.restart, *dem, with_air ? &air : nullptr, diag, counters);
    if (stored != info.resolved_config) {
      // Name the differing lines (time.end and output keys usually; anything else changes the physics).
      auto lines = [](const std::string& s) {
        std::set<std::string> out;
        std::istringstream in(s);
        for (std::string l; std::getline(in, l);) out.insert(l);
        return out;
      };
      const auto a = lines(stored), b = lines(info.resolved_config);
      std::vector<std::string> diff;
      for (const auto& l : b)
        if (!a.count(l)) diff.push_back(l);
      fmt::print(stderr, "cgdem: warning: the case differs from the one that wrote {} in: {} (continuing)\n",
                 info.restart, fmt::join(diff, " | "));
    }
    fmt::print("restarting from {} at t = {:.6g} s (DEM step {})\n", info.restart, dem->time(), dem->steps());
  }

  fmt::print("cgdem {}: {} particles, {} species, {} wall parts, dt = {:g} s, t = {:g} .. {:g} s\n", kGitRevision,
             dem->particles().size(), c.species.size(), dem->scene().parts().size(), c.dem.dt, c.t_start, c.t_end);
  if (with_air)
    fmt::print("air: {} x {} x {} cells of {:g} m, fluid step <= {:g} s, pressure {} (tol {:g}), {}-way coupling\n",
               air_case.grid.nx, air_case.grid.ny, air_case.grid.nz, air_case.grid.dx, air_case.coupled.dt_fluid_max,
               air_case.fluid.pressure.method, air_case.fluid.pressure.rel_tol, air_case.coupled.feedback ? "two" : "one");
  if (with_air && air_case.coupled.coupling == DragCoupling::Implicit)
    fmt::print("drag: implicit (the coefficient at the step's end velocity), KINSOL {} (tol {:g} m/s, at most {} "
               "iterations{})\n",
               air_case.coupled.implicit.method, air_case.coupled.implicit.tol, air_case.coupled.implicit.max_iterations,
               air_case.coupled.implicit.method == "anderson"
                   ? fmt::format(", depth {}", air_case.coupled.implicit.depth)
                   : std::string());
  if (!with_air)
    fmt::print("air: none (vacuum)\n");
  fmt::print("shortest collision time {:.4g} s ({:.1f} steps); set-up {:.2f} s\n", dem->min_collision_time(),
             dem->min_collision_time() / c.dem.dt, setup_clock.seconds());

  io::SnapshotSeries snapshots(c.output.dir, "particles", attrs, restart, c.output.compression);
  std::unique_ptr<io::GridSnapshotSeries> air_snapshots;
  if (with_air) air_snapshots = std::make_unique<io::GridSnapshotSeries>(c.output.dir, "air", attrs, restart,
                                                                        c.output.compression);
  // Time series: on a restart the rows after the checkpoint's time are dropped and the
  // file continues; otherwise it starts afresh.
  const std::string series_comment = "case " + info.case_file;
  auto open_csv = [&](const std::string& name, const io::CsvColumns& columns) {
    return open_series(c.output.dir, name, columns, series_comment, restart, dem->time());
  };
  std::unique_ptr<io::CsvSeries> energy = open_csv("energy.csv", energy_csv_columns());
  // diagnostics.csv is sampled uniformly (run_schedule.hpp): its rows fall on a grid whose
  // interval is a whole multiple of at least the largest fluid step.
  const double largest_step = with_air ? air_case.coupled.dt_fluid_max : 0.0;
  const std::string diag_note = OutputSchedule(c, diag_spec, dem->time(), largest_step).diagnostics_note(diag_spec.interval);
  std::unique_ptr<io::CsvSeries> diag_csv =
      diag_spec.enabled ? open_series(c.output.dir, "diagnostics.csv", diag.csv_columns(), series_comment, restart,
                                      dem->time(), {diag_note})
                        : nullptr;
  std::unique_ptr<io::CsvSeries> surface_csv =
      diag_spec.enabled ? open_csv("shoe_surface.csv", diag.surface_columns()) : nullptr;
  const std::string last_good = (out / "last_good.h5").string();
  const std::string checkpoint = (out / "checkpoint.bin").string();
  // Parcels are never lost silently: the count (present + removed) must stay what it was,
  // and every new departure or tunnelling is announced when it is seen.
  const long n_total = static_cast<long>(dem->particles().size()) + dem->removed();
  long seen_removed = dem->removed(), seen_inside = 0;
  auto account_parcels = [&](long inside) {
    const long now = static_cast<long>(dem->particles().size()) + dem->removed();
    if (now != n_total)
      throw RunError(fmt::format("t = {:.6g} s: {} parcels present + {} removed = {}, but the run has {} "
                                 "(a parcel was lost without being counted)",
                                 dem->time(), dem->particles().size(), dem->removed(), now, n_total));
    if (dem->removed() > seen_removed)
      fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} more parcel(s) left the domain ({} in all)\n",
                 dem->time(), dem->removed() - seen_removed, dem->removed());
    if (inside > seen_inside)
      fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} parcel centre(s) inside a wall (tunnelled)\n",
                 dem->time(), inside);
    seen_removed = dem->removed();
    seen_inside = inside;
  };
  auto write_energy = [&]() {
    EnergyBudget e = dem->energy();
    e.work_fluid = dem->fluid_work();
    const long inside = count_inside_walls(*dem);
    account_parcels(inside);
    energy->row(energy_csv_row(*dem, e, inside));
    energy->flush();
  };
  auto diagnostics_now = [&]() {
    return diag.row(dem->time(), dem->particles(), with_air ? &air : nullptr, with_air ? &air_case.fluid : nullptr,
                    with_air ? &fluid->ibm().alpha_cell : nullptr);
  };
  // The rows a step passed (interpolated between `before`, the state at the step's start, and
  // the state at its end), then the state at its end when it is due.
  std::optional<DiagnosticsRow> before;
  auto write_diagnostics = [&](const std::vector<double>& passed = {}, bool at_end = true) {
    if (!diag_csv) return;
    const DiagnosticsRow now = diagnostics_now();
    for (double tk : passed) diag_csv->row(diag.csv_line(before ? interpolate_row(*before, now, tk) : now));
    if (at_end) diag_csv->row(diag.csv_line(now));
    diag_csv->flush();
    before.reset();
  };
  auto write_surface = [&]() {
    if (!surface_csv) return;
    surface_csv->rows(diag.surface_rows(dem->time(), dem->particles()));
    surface_csv->flush();
  };
  auto check_health = [&]() {
    check_particles(*dem, c.output.max_speed);
    if (with_air) check_air(air, c.output.max_speed, counters.fluid_steps);
  };
  auto write_snapshot = [&]() {
    io::ParticleTable t = to_table(dem->particles());
    snapshots.write(dem->steps(), dem->time(), t);
    if (with_air) write_air_snapshot(*air_snapshots, dem->steps(), air, fluid->ibm().alpha_cell);
    // atomic: always a consistent state
    io::write_particles_h5(last_good, t, attrs, c.output.compression, io::Instant{dem->time(), dem->steps()});
  };

  auto write_checkpoint_now = [&]() {
    write_checkpoint(checkpoint, info.resolved_config, *dem, with_air ? &air : nullptr, diag, counters);
  };

  check_health();
  if (!restart) {
    diag.observe(dem->time(), dem->particles());
    write_energy();
    write_diagnostics();
    write_surface();
    write_snapshot();
    write_checkpoint_now();
  }
  // The run loop's own phases (everything that is neither DEM, coupling nor air).
  PhaseTimers out_timers;
  const int t_observe = out_timers.id("die diagnostics"), t_series = out_timers.id("CSV series");
  const int t_snap = out_timers.id("snapshots"), t_ckpt = out_timers.id("checkpoints");
  OutputSchedule schedule(c, diag_spec, dem->time(), largest_step);
  ProgressLine progress(c, dem->time(), isatty(STDOUT_FILENO));
  const bool tty = isatty(STDOUT_FILENO);
  const long observe_every = std::max(1L, std::lround(1e-4 / c.dem.dt));  // vacuum: diagnostics every 0.1 ms
  long particle_steps = 0;
  while (!schedule.finished(dem->time())) {
    if (diag_csv && schedule.passes_diagnostics(dem->time(), dem->time() + (with_air ? coupled->substeps() : 1) * c.dem.dt)) {
      auto ts = out_timers.scope(t_observe);
      before = diagnostics_now();  // this step passes a row time: its start state, to interpolate
    }
    if (with_air) {
      const long before = dem->steps();
      CoupledStepStats st = coupled->step();
      particle_steps += (dem->steps() - before) * static_cast<long>(dem->particles().size());
      count_fluid_step(counters, st, dem->time());
      count_drag_step(drag_counters, st);
      auto ts = out_timers.scope(t_observe);
      diag.observe(dem->time(), dem->particles(), st.dt_fluid);  // the next step: as long as this one
    } else {
      dem->step();
      particle_steps += static_cast<long>(dem->particles().size());
      if (dem->steps() % observe_every == 0) {
        auto ts = out_timers.scope(t_observe);
        diag.observe(dem->time(), dem->particles(), observe_every * c.dem.dt);
      }
    }
    const double t = dem->time();
    const OutputSchedule::Due due = schedule.after_step(t);
    if (due.energy) {
      auto ts = out_timers.scope(t_series);
      check_health();
      write_energy();
    }
    if (due.diagnostics || !due.diagnostics_passed.empty()) {
      auto ts = out_timers.scope(t_series);
      write_diagnostics(due.diagnostics_passed, due.diagnostics);
    }
    if (due.surface) {
      auto ts = out_timers.scope(t_series);
      write_surface();
    }
    if (due.snapshot) {
      auto ts = out_timers.scope(t_snap);
      write_snapshot();
    }
    if (due.checkpoint) {
      auto ts = out_timers.scope(t_ckpt);
      check_health();
      write_checkpoint_now();
    }
    if (due.settled) {  // the state of t = 0, to rerun the filling without settling again
      auto ts = out_timers.scope(t_ckpt);
      check_health();
      write_checkpoint((out / "settled.bin").string(), info.resolved_config, *dem, with_air ? &air : nullptr, diag,
                       counters);
      fmt::print("{}settled state at t = {:.6g} s saved: {} (rerun the filling with --restart)\n", tty ? "\n" : "", t,
                 (out / "settled.bin").string());
    }
    progress.update(t, particle_steps, due.last);
  }
  progress.finish();
  energy.reset(), diag_csv.reset(), surface_csv.reset();

  if (diag_spec.enabled) write_impacts(c.output.dir, diag, series_comment);

  const double wall = progress.seconds();
  io::write_metrics((out / "metrics.csv").string(),
                    run_metrics(c.output.dir, *dem, diag_spec.enabled, diag.front_impact(), DieRun{diag_spec.die, with_air}));
  EnergyBudget e = dem->energy();
  fmt::print("\n{}", dem->timers().table("per-phase time (DEM)"));
  if (with_air) {
    fmt::print("{}", coupled->timers().table("per-phase time (coupling)"));
    fmt::print("{}", fluid->timers().table("per-phase time (air)"));
    print_fluid_counters(counters);
    if (drag_counters.steps > 0) print_drag_counters(drag_counters);
  }
  fmt::print("{}", out_timers.table("per-phase time (output)"));
  {
    const double t_dem = dem->timers().total(), t_out = out_timers.total();
    const double t_cpl = with_air ? coupled->timers().total() : 0.0, t_air = with_air ? fluid->timers().total() : 0.0;
    fmt::print("wall {:.1f} s = DEM {:.1f} + coupling {:.1f} + air {:.1f} + output {:.1f} + other {:.1f} s\n", wall,
               t_dem, t_cpl, t_air, t_out, wall - t_dem - t_cpl - t_air - t_out);
  }
  fmt::print("DEM steps {}, wall {:.1f} s, {:.3g} particle-steps/s, neighbour-list builds {}\n", dem->steps(), wall,
             particle_steps / std::max(wall, 1e-9), dem->neighbor_builds());
  fmt::print("particles {} (left the domain: {}, centre inside a wall: {}), solid mass {:.6g} kg\n",
             dem->particles().size(), dem->removed(), count_inside_walls(*dem), e.mass);
  if (diag_spec.enabled) print_front(diag, diag_spec);
  fmt::print("state digest {:016x} at t = {:.9g} s\n", state_digest(*dem, with_air ? &air : nullptr), dem->time());
  fmt::print("outputs in {}: energy.csv, metrics.csv{}, particles.xdmf (+ particles_*.h5){}, last_good.h5, "
             "checkpoint.bin, config.resolved.toml\n",
             c.output.dir, diag_spec.enabled ? ", diagnostics.csv, shoe_surface.csv, impacts.csv" : "",
             with_air ? ", air.xdmf (+ air_*.h5)" : "");
  return 0;
}

}  // namespace cgdem::app
