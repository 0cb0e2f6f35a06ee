#include "app/particle_run.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "app/run_checks.hpp"
#include "app/run_outputs.hpp"
#include "app/run_schedule.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "solvers/run/particle_stepper.hpp"
#include "solvers/run/run_checkpoint.hpp"
#include "solvers/run/run_driver.hpp"

namespace cgdem::app {

namespace {

namespace fs = std::filesystem;

// The lines of `now` that `stored` lacks (the keys a restart changed).
std::vector<std::string> changed_lines(const std::string& stored, const std::string& now) {
  auto lines = [](const std::string& s) {
    std::set<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) out.insert(l);
    return out;
  };
  const auto a = lines(stored), b = lines(now);
  std::vector<std::string> diff;
  for (const auto& l : b)
    if (!a.count(l)) diff.push_back(l);
  return diff;
}

// output.energy_accounts of a resolved configuration (true when it does not say).
bool energy_accounts_in(const std::string& config) {
  Config cfg = Config::from_string(config, "the checkpoint's configuration");
  const std::optional<Section> output = cfg.root().optional_section("output");
  return !output || output->boolean_or("energy_accounts", true);
}

// The lines of the tables [particles], [particles.*] and [[particles.*]] of a resolved
// configuration, in order: what decides the neighbour-list skin (its value, or a tenth of
// the largest parcel diameter).
std::string particles_tables(const std::string& config) {
  std::istringstream in(config);
  std::string out;
  bool inside = false;
  for (std::string l; std::getline(in, l);) {
    // A table header is [name] or [[name]], name starting with a letter; a line of a
    // multi-line array may also start with '[' (a nested array), never with a letter after it.
    const size_t k = l.find_first_not_of('[');
    if (k >= 1 && k <= 2 && k < l.size() && std::isalpha(static_cast<unsigned char>(l[k])) && l.back() == ']') {
      const std::string name = l.substr(k);
      inside = name.rfind("particles]", 0) == 0 || name.rfind("particles.", 0) == 0;
    }
    if (inside) out += l + '\n';
  }
  return out;
}

class ParticleRun final : public run::Run {
 public:
  ParticleRun(run::Domain& domain, const DemCase& c, const AirCase& air, const DiagnosticsSpec& spec,
              const RunInfo& info)
      : domain_(domain), comm_(domain.comm()), c_(c), air_(air), spec_(spec), info_(info),
        diag_(spec, species_values(c, &Species::mass), species_values(c, &Species::diameter)),
        tty_(comm_.root() && isatty(STDOUT_FILENO)) {}

  bool set_up() override;
  void check_health() override;
  void write_initial() override;
  bool finished() const override { return schedule_->finished(s_->dem().time()); }
  void step() override;
  void observe() override;
  run::Due due() override;
  void write_due() override { write(due_); }
  void progress(bool last) override {
    if (comm_.root()) progress_->update(s_->dem().time(), particle_steps_, last);
  }
  int report() override;

 private:
  static std::vector<double> species_values(const DemCase& c, double (Species::*f)() const) {
    std::vector<double> v;
    for (const auto& s : c.species) v.push_back((s.*f)());
    return v;
  }
  std::string path(const char* name) const { return (fs::path(c_.output.dir) / name).string(); }
  void write_config();
  void restore();
  void print_banner(double setup_seconds);
  void write(const OutputSchedule::Due& d);
  void print_report(const run::Totals& t, long inside, const std::string& digest, const std::string& ranks,
                    double wall);

  run::Domain& domain_;
  run::RunComm& comm_;
  const DemCase& c_;
  const AirCase& air_;
  const DiagnosticsSpec& spec_;
  const RunInfo& info_;
  DieDiagnostics diag_;  // rank 0's is the one that counts
  RunCounters counters_;
  DragCounters drag_counters_;  // implicit drag coupling, since this process started (not checkpointed)
  std::unique_ptr<run::ParticleStepper> s_;
  std::unique_ptr<OutputSchedule> schedule_;
  std::unique_ptr<RunOutputs> out_;
  std::unique_ptr<ProgressLine> progress_;
  // The run loop's own phases (everything that is neither DEM, coupling nor air).
  PhaseTimers timers_;
  const int t_observe_ = timers_.id("die diagnostics"), t_series_ = timers_.id("CSV series");
  const int t_snap_ = timers_.id("snapshots"), t_ckpt_ = timers_.id("checkpoints");
  const int t_health_ = timers_.id("health checks");
  const long observe_every_ = std::max(1L, std::lround(1e-4 / c_.dem.dt));  // vacuum: diagnostics every 0.1 ms
  run::StepDone last_;
  OutputSchedule::Due due_;
  long particle_steps_ = 0, n_present_ = 0;  // progress figure: parcels present at the start
  // Where this run (piece) started, for timings.csv: time, steps, builds, fluid steps, set-up [s].
  double t_first_ = 0, setup_seconds_ = 0;
  long steps_first_ = 0, builds_first_ = 0, fluid_first_ = 0;
  int written_on_ = 1;                       // ranks that wrote the checkpoint
  bool tty_;
};

bool ParticleRun::set_up() {
  const bool restart = !info_.restart.empty();
  // A restart that the checkpoint refuses leaves the folder's configuration as it was.
  if (!restart) write_config();
  Stopwatch setup_clock;
  const std::string case_dir = fs::path(info_.case_file).parent_path().string();
  std::unique_ptr<DemSolver> dem;
  comm_.together("set-up", false, [&] { dem = build_solver(c_, case_dir.empty() ? "." : case_dir); });
  std::optional<run::AirSpec> air;
  if (air_.enabled) air = run::AirSpec{air_.grid, air_.fluid, air_.coupled, air_.exchange, air_.mpi_preconditioner};
  s_ = std::make_unique<run::ParticleStepper>(domain_, std::move(dem), std::move(air));
  if (restart) {
    restore();
    write_config();
  } else {
    s_->place_parcels();
    s_->make_air();
  }
  const run::Totals t = s_->totals();
  n_present_ = t.present;
  setup_seconds_ = setup_clock.seconds();
  print_banner(setup_seconds_);
  const double now = s_->dem().time();
  t_first_ = now, steps_first_ = s_->dem().steps(), builds_first_ = s_->dem().neighbor_builds();
  fluid_first_ = counters_.fluid_steps;
  // diagnostics.csv is sampled uniformly (run_schedule.hpp): its rows fall on a grid whose
  // interval is a whole multiple of at least the largest fluid step.
  schedule_ = std::make_unique<OutputSchedule>(c_, spec_, now, air_.enabled ? air_.coupled.dt_fluid_max : 0.0);
  out_ = std::make_unique<RunOutputs>(
      *s_, c_, spec_, diag_, counters_,
      OutputContext{info_.case_file, info_.resolved_config, restart, schedule_->diagnostics_note(spec_.interval)});
  progress_ = std::make_unique<ProgressLine>(c_, now, tty_);
  return restart;
}

void ParticleRun::write_config() {
  const std::string ranks = comm_.size() > 1 ? fmt::format("# run on {} MPI ranks\n", comm_.size()) : "";
  comm_.together("output folder", true, [&] {
    fs::create_directories(c_.output.dir);
    io::write_file_atomic(path("config.resolved.toml"),
                          fmt::format("# cgdem {} resolved configuration of {}\n{}{}", kGitRevision, info_.case_file,
                                      ranks, info_.resolved_config));
  });
}

void ParticleRun::restore() {
  std::optional<run::CheckpointReader> from;
  comm_.together("restart", false, [&] { from.emplace(info_.restart); });
  if (comm_.root()) {
    if (from->revision() != kGitRevision)
      fmt::print(stderr, "cgdem: warning: the checkpoint was written by revision {}, this is {}\n", from->revision(),
                 kGitRevision);
    if (from->config() != info_.resolved_config)  // time.end and output keys usually; anything else changes the physics
      fmt::print(stderr, "cgdem: warning: the case differs from the one that wrote {} in: {} (continuing)\n",
                 info_.restart, fmt::join(changed_lines(from->config(), info_.resolved_config), " | "));
  }
  // The accounts are totals since the start: a run that did not keep them cannot take them
  // up halfway. A run that kept them may drop them (a production run from a settled state),
  // but not into an energy.csv whose header says that its columns were computed.
  if (const bool before = energy_accounts_in(from->config()); before != c_.dem.accounts) {
    if (!before)
      throw Error(fmt::format("restart: {} was written with output.energy_accounts = false: the energy books are "
                              "totals since the start and cannot be taken up halfway; continue without them, or "
                              "start again from the beginning",
                              info_.restart));
    if (fs::exists(path("energy.csv")))
      throw Error(fmt::format("restart: {} was written with the energy accounts, and output.energy_accounts = false "
                              "would continue {}, whose columns say that they were computed; restart into another "
                              "output folder (--output), or keep the accounts",
                              info_.restart, path("energy.csv")));
  }
  from->restore(*s_, [&](io::ArchiveReader& r) { RunOutputs::load_observers(r, diag_, counters_); });
  written_on_ = from->ranks();
  // The checkpoint's neighbour lists are complete for the skin they were built with. A case
  // whose [particles] differ may have another skin: the first step rebuilds the lists
  // (trusting them for a larger skin would miss contacts).
  if (particles_tables(from->config()) != particles_tables(info_.resolved_config)) {
    s_->dem().rebuild_lists_at_next_step();
    if (comm_.root())
      fmt::print(stderr, "cgdem: [particles] differs from the checkpoint's: the neighbour lists are rebuilt at the "
                         "first step (skin {:g} m)\n",
                 s_->dem().neighbor_list().skin);
  }
  if (comm_.root() && air_.enabled && !from->with_air())
    fmt::print("cgdem: {} holds no air (a run in vacuum): the air starts at rest around its parcels at t = {:.6g} s\n",
               info_.restart, s_->dem().time());
}

void ParticleRun::print_banner(double setup_seconds) {
  if (!comm_.root()) return;
  DemSolver& dem = s_->dem();
  const double min_collision = dem.min_collision_time();
  if (!info_.restart.empty())
    fmt::print("restarting from {} at t = {:.6g} s (DEM step {}){}\n", info_.restart, dem.time(), dem.steps(),
               written_on_ > 1 ? fmt::format(", written on {} ranks", written_on_) : "");
  fmt::print("cgdem {}: {} particles, {} species, {} wall parts, dt = {:g} s, t = {:g} .. {:g} s\n", kGitRevision,
             n_present_, c_.species.size(), dem.scene().parts().size(), c_.dem.dt, c_.t_start, c_.t_end);
  if (const std::string d = domain_.describe(); !d.empty()) fmt::print("{}\n", d);
  if (air_.enabled) {
    const fluid::MacGrid& g = air_.grid;
    fmt::print("air: {} x {} x {} cells of {:g} m, fluid step <= {:g} s, {} (tol {:g}), {}-way coupling\n", g.nx, g.ny,
               g.nz, g.dx, air_.coupled.dt_fluid_max, s_->air_share().pressure_text, air_.fluid.pressure.rel_tol,
               air_.coupled.feedback ? "two" : "one");
  } else {
    fmt::print("air: none (vacuum)\n");
  }
  if (air_.enabled && air_.coupled.coupling == DragCoupling::Implicit) {
    const ImplicitDragOptions& o = air_.coupled.implicit;
    fmt::print("drag: implicit (the coefficient at the step's end velocity), KINSOL {} (tol {:g} m/s, at most {} "
               "iterations{})\n",
               o.method, o.tol, o.max_iterations, o.method == "anderson" ? fmt::format(", depth {}", o.depth) : "");
  }
  fmt::print("shortest collision time {:.4g} s ({:.1f} steps); set-up {:.2f} s\n", min_collision,
             min_collision / c_.dem.dt, setup_seconds);
}

void ParticleRun::check_health() {
  auto ts = timers_.scope(t_health_);
  const DemSolver& dem = s_->dem();
  comm_.together("health check", false, [&] {
    check_particles(dem.particles(), dem.owned(), dem.steps(), dem.time(), c_.output.max_speed);
    if (air_.enabled) check_air(s_->air(), c_.output.max_speed, counters_.fluid_steps, s_->air_share().first_cell);
  });
}

void ParticleRun::write_initial() {
  out_->observe(0);
  OutputSchedule::Due all;
  all.energy = all.diagnostics = all.surface = all.snapshot = all.checkpoint = true;
  write(all);
}

void ParticleRun::step() {
  const double t = s_->dem().time();
  if (spec_.enabled && schedule_->passes_diagnostics(t, s_->next_step_end())) {
    auto ts = timers_.scope(t_observe_);
    out_->remember_step_start();  // this step passes a row time: its start state, to interpolate
  }
  last_ = s_->step();
  particle_steps_ += last_.dem_steps * n_present_;
  if (last_.coupled) {
    count_fluid_step(counters_, *last_.coupled, s_->dem().time(), comm_.root());
    count_drag_step(drag_counters_, *last_.coupled);
    auto ts = timers_.scope(t_series_);
    out_->air_step(s_->dem().time(), *last_.coupled);
  }
}

void ParticleRun::observe() {
  auto ts = timers_.scope(t_observe_);
  if (last_.coupled)
    out_->observe(last_.dt);  // the next step: as long as this one
  else if (s_->dem().steps() % observe_every_ == 0)
    out_->observe(observe_every_ * c_.dem.dt);
}

run::Due ParticleRun::due() {
  due_ = schedule_->after_step(s_->dem().time());
  return {due_.energy || due_.checkpoint || due_.settled, due_.last};
}

void ParticleRun::write(const OutputSchedule::Due& d) {
  if (d.energy) {
    auto ts = timers_.scope(t_series_);
    out_->energy();
  }
  if (d.diagnostics || !d.diagnostics_passed.empty()) {
    auto ts = timers_.scope(t_series_);
    out_->diagnostics(d.diagnostics_passed, d.diagnostics);
  }
  if (d.surface) {
    auto ts = timers_.scope(t_series_);
    out_->surface();
  }
  if (d.snapshot) {
    auto ts = timers_.scope(t_snap_);
    out_->snapshot();
  }
  if (d.checkpoint) {
    auto ts = timers_.scope(t_ckpt_);
    out_->checkpoint(path("checkpoint.bin"));
  }
  if (d.settled) {  // the state of t = 0, to rerun the filling without settling again
    auto ts = timers_.scope(t_ckpt_);
    out_->checkpoint(path("settled.bin"));
    if (comm_.root())
      fmt::print("{}settled state at t = {:.6g} s saved: {} (rerun the filling with --restart, on any number of MPI "
                 "ranks)\n",
                 tty_ ? "\n" : "", s_->dem().time(), path("settled.bin"));
  }
}

int ParticleRun::report() {
  if (comm_.root()) progress_->finish();
  DemSolver& dem = s_->dem();
  const run::Totals t = s_->totals();
  const long inside = comm_.sum(count_inside_walls(dem.scene(), dem.time(), dem.particles(), dem.owned()));
  out_->finish(t);
  const std::string digest =
      comm_.size() == 1
          ? fmt::format("state digest {:016x}", run::state_digest(dem, air_.enabled ? &s_->air() : nullptr))
          : fmt::format("portable state digest {:016x}", run::state_digest(s_->portable_state()));
  const std::string ranks = domain_.report(dem, air_.enabled ? s_->air_share().grid.cells() : 0);
  rusage use{};
  getrusage(RUSAGE_SELF, &use);  // ru_maxrss in KiB (Linux)
  const long peak_kib = comm_.min_max(static_cast<long>(use.ru_maxrss))[1];
  comm_.together("final report", true, [&] {
    const double wall = progress_->seconds();
    print_report(t, inside, digest, ranks, wall);
    RunPiece piece;
    piece.t_start = t_first_, piece.t_end = dem.time();
    piece.threads = omp_get_max_threads(), piece.ranks = comm_.size();
    piece.wall = wall, piece.set_up = setup_seconds_;
    piece.dem_steps = dem.steps() - steps_first_, piece.fluid_steps = counters_.fluid_steps - fluid_first_;
    piece.list_builds = dem.neighbor_builds() - builds_first_, piece.particles = t.present;
    piece.peak_rss_mib = peak_kib / 1024.0;
    std::vector<std::pair<std::string, const PhaseTimers*>> groups = {{"dem", &dem.timers()}};
    if (air_.enabled) {
      groups.emplace_back("coupling", &s_->coupled().timers());
      groups.emplace_back("air", &s_->fluid().timers());
    }
    groups.emplace_back("output", &timers_);
    out_->timings(timings_rows(piece, groups));
  });
  return 0;
}

void ParticleRun::print_report(const run::Totals& t, long inside, const std::string& digest,
                               const std::string& ranks, double wall) {
  DemSolver& dem = s_->dem();
  const std::string rank0 = comm_.size() > 1 ? ", rank 0" : "";
  fmt::print("\n{}", dem.timers().table("per-phase time (DEM" + rank0 + ")"));
  double t_cpl = 0, t_air = 0;
  if (air_.enabled) {
    fmt::print("{}", s_->coupled().timers().table("per-phase time (coupling" + rank0 + ")"));
    fmt::print("{}", s_->fluid().timers().table("per-phase time (air" + rank0 + ")"));
    print_fluid_counters(counters_);
    const auto nodes = s_->coupled().capacity_nodes();
    if (nodes[0] + nodes[1] > 0)
      fmt::print("kernel capacities next to walls: {} node values, {:.1f} % of them from the cache (static walls, or no "
                 "body moved since they were evaluated)\n", nodes[0] + nodes[1], 100.0 * nodes[0] / (nodes[0] + nodes[1]));
    if (drag_counters_.steps > 0) print_drag_counters(drag_counters_);
    t_cpl = s_->coupled().timers().total(), t_air = s_->fluid().timers().total();
  }
  fmt::print("{}", timers_.table("per-phase time (output" + rank0 + ")"));
  const double t_dem = dem.timers().total(), t_out = timers_.total();
  fmt::print("wall {:.1f} s = DEM {:.1f} + coupling {:.1f} + air {:.1f} + output {:.1f} + other {:.1f} s\n", wall,
             t_dem, t_cpl, t_air, t_out, wall - t_dem - t_cpl - t_air - t_out);
  fmt::print("DEM steps {}, wall {:.1f} s, {:.3g} particle-steps/s{}, neighbour-list builds {}\n", dem.steps(), wall,
             particle_steps_ / std::max(wall, 1e-9),
             comm_.size() > 1 ? fmt::format(" on {} ranks", comm_.size()) : "", dem.neighbor_builds());
  fmt::print("{}", ranks);
  fmt::print("particles {} (left the domain: {}, centre inside a wall: {}), solid mass {:.6g} kg\n", t.present,
             t.removed, inside, t.energy.mass);
  if (spec_.enabled) print_front(diag_, spec_);
  fmt::print("{} at t = {:.9g} s\n", digest, dem.time());
  fmt::print("outputs in {}: energy.csv, metrics.csv, timings.csv{}, particles.xdmf (+ particles_*.h5){}, last_good.h5, "
             "checkpoint.bin, config.resolved.toml\n",
             c_.output.dir, spec_.enabled ? ", diagnostics.csv, shoe_surface.csv, impacts.csv" : "",
             air_.enabled ? ", air_steps.csv, air.xdmf (+ air_*.h5)" : "");
}

}  // namespace

int run_particle_case(run::Domain& domain, const DemCase& c, const AirCase& air, const DiagnosticsSpec& diag,
                      const RunInfo& info) {
  ParticleRun r(domain, c, air, diag, info);
  return run::drive(r);
}

}  // namespace cgdem::app
