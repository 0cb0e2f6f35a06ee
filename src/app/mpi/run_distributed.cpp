#include "app/mpi/run_distributed.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/checkpoint.hpp"
#include "app/energy_csv.hpp"
#include "app/run_checks.hpp"
#include "app/run_metrics.hpp"
#include "app/run_schedule.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "parallel/mpi/distributed_dem.hpp"
#include "parallel/mpi/exchange.hpp"
#include "parallel/mpi/gather.hpp"
#include "particles/particle_io.hpp"

namespace cgdem::app {

namespace {

constexpr uint32_t kPortableVersion = 1;

struct Ranks {
  MPI_Comm comm;
  int rank = 0, size = 1;
};

long sum_over(const Ranks& r, long v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_SUM, r.comm), "MPI_Allreduce", "run");
  return v;
}
double sum_over(const Ranks& r, double v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, r.comm), "MPI_Allreduce", "run");
  return v;
}

// f() on every rank (on rank 0 only when root_only); a cgdem::Error on any rank stops
// every rank at this point (parallel::RaisedTogether, carrying the message on the rank
// that found it). No rank is then left waiting in the next collective call.
template <class F>
void together(const Ranks& r, const char* what, bool root_only, F&& f) {
  std::string error;
  if (!root_only || r.rank == 0) {
    try {
      f();
    } catch (const Error& e) {
      error = e.what();
    }
  }
  parallel::raise_together(r.comm, r.rank, error, what);
}

// What a portable checkpoint holds besides the parcels: the run's position and the totals
// over all ranks of the removed parcels and their energy accounts.
struct RunHeader {
  double t = 0;
  long steps = 0, removed = 0, builds = 0;
  double removed_damping = 0, removed_friction = 0, removed_walls = 0, removed_fluid = 0;
  int ranks = 1;  // that wrote it (information)
};

void write_portable_checkpoint(const std::string& path, const std::string& config, const RunHeader& h,
                               const parallel::PortableState& s, const DieDiagnostics& diag,
                               const RunCounters& counters) {
  io::ArchiveWriter w;
  w.put(kPortableCheckpointMagic), w.put(kPortableVersion);
  w.put_string(kGitRevision), w.put_string(config);
  w.put<uint8_t>(0);  // no air
  w.tag("run");
  w.put(h);
  parallel::save(w, s);
  diag.save(w);
  w.tag("counters");
  w.put(counters);
  w.tag("end");
  io::write_file_atomic(path, w.bytes());
}

std::string read_portable_checkpoint(const std::string& path, RunHeader& h, parallel::PortableState& s,
                                     DieDiagnostics& diag, RunCounters& counters) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read checkpoint " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  io::ArchiveReader r(ss.str(), path);
  if (r.get<uint64_t>() != kPortableCheckpointMagic)
    throw Error(path + " is not a checkpoint of a run over MPI ranks (a single-process checkpoint restarts "
                       "without mpirun)");
  if (const auto v = r.get<uint32_t>(); v != kPortableVersion)
    throw Error(fmt::format("{}: portable checkpoint format {} (this build reads {})", path, v, kPortableVersion));
  const std::string revision = r.get_string();
  std::string config = r.get_string();
  if (revision != kGitRevision)
    fmt::print(stderr, "cgdem: warning: the checkpoint was written by revision {}, this is {}\n", revision,
               kGitRevision);
  if (r.get<uint8_t>() != 0) throw Error(path + ": a checkpoint with air (not supported over MPI ranks)");
  r.tag("run");
  r.get(h);
  parallel::load(r, s);
  diag.load(r);
  r.tag("counters");
  r.get(counters);
  r.tag("end");
  return config;
}

uint64_t digest(const parallel::PortableState& s) {
  io::ArchiveWriter w;
  parallel::save(w, s);
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char ch : w.bytes()) h = (h ^ ch) * 1099511628211ULL;
  return h;
}

}  // namespace

int run_case_distributed(MPI_Comm comm, const DemCase& c, const AirCase& air_case, const DiagnosticsSpec& diag_spec,
                         const RunInfo& info) {
  namespace fs = std::filesystem;
  Ranks R{comm};
  MPI_Comm_rank(comm, &R.rank);
  MPI_Comm_size(comm, &R.size);
  const bool root = R.rank == 0;
  if (air_case.enabled)
    throw ConfigError(fmt::format(
        "this case has air ([air]); on {} MPI ranks `cgdem run` runs particle cases in vacuum only: the air's halo "
        "exchange and distributed pressure solve are not yet part of the run (docs/scale_out.md). Run it in one "
        "process (without mpirun), or without [air]",
        R.size));
  const fs::path out(c.output.dir);
  const std::string case_dir = fs::path(info.case_file).parent_path().string();
  io::Attributes attrs{{"cgdem_revision", kGitRevision}, {"config", info.resolved_config},
                       {"mpi_ranks", std::to_string(R.size)}};
  together(R, "output folder", true, [&] {
    fs::create_directories(out);
    io::write_file_atomic((out / "config.resolved.toml").string(),
                          fmt::format("# cgdem {} resolved configuration of {}\n# run on {} MPI ranks\n{}",
                                      kGitRevision, info.case_file, R.size, info.resolved_config));
  });

  Stopwatch setup_clock;
  std::unique_ptr<DemSolver> dem;
  together(R, "set-up", false, [&] { dem = build_solver(c, case_dir.empty() ? "." : case_dir); });
  std::vector<double> sp_mass, sp_d;
  for (const auto& s : c.species) sp_mass.push_back(s.mass()), sp_d.push_back(s.diameter());
  DieDiagnostics diag(diag_spec, sp_mass, sp_d);  // rank 0's is the one that counts
  RunCounters counters;
  const bool restart = !info.restart.empty();
  RunHeader header;
  // Blocks that share the parcels out evenly (every rank holds all of them here): the block
  // counts from the parcels' extent (the least cut area through them), the cuts at the
  // quantiles of their positions, no block narrower than one interaction range.
  const geometry::Aabb& box = c.dem.domain;
  std::vector<Vec3> where;
  double r_max = 0;
  for (const auto& s : c.species) r_max = std::max(r_max, 0.5 * s.diameter());
  const double range = 2 * r_max + dem->params().skin;
  parallel::PortableState from;  // a restart's parcels (read once here, kept for below)
  std::string stored_config;
  if (restart)
    together(R, "restart", false,
             [&] { stored_config = read_portable_checkpoint(info.restart, header, from, diag, counters); });
  for (const Vec3& x : restart ? from.p.x : dem->particles().x) where.push_back(x);
  Vec3 lo = box.hi, hi = box.lo;
  for (const Vec3& x : where) lo = cmin(lo, x), hi = cmax(hi, x);
  Vec3 extent;
  for (int a = 0; a < 3; ++a) extent[a] = std::max(hi[a] - lo[a], 0.0) + range;
  const parallel::Decomposition d =
      R.size == 1 ? parallel::Decomposition(box, {1, 1, 1})
                  : parallel::Decomposition(box, parallel::balanced_cuts(box, parallel::choose_dims(R.size, extent),
                                                                         where, range));
  const long n_case = static_cast<long>(dem->particles().size());  // every rank built the whole case
  {
    Particles& p = dem->particles();
    if (restart) {
      const parallel::PortableState& s = from;
      if (root && stored_config != info.resolved_config)
        fmt::print(stderr, "cgdem: warning: the case differs from the one that wrote {} (continuing)\n",
                   info.restart);
      together(R, "restart", false, [&] {
        if (static_cast<long>(s.size()) + header.removed != n_case)
          throw Error(fmt::format("checkpoint {} holds {} particles (+{} removed), the case inserts {}", info.restart,
                                  s.size(), header.removed, n_case));
        Particles mine;
        NeighborList lists;
        parallel::restore(s, [&](const Vec3& x) { return d.owner_of(x) == R.rank; }, mine, lists);
        EnergyBudget removed_accounts;
        if (root) {  // the removed parcels' totals are booked once, on rank 0
          removed_accounts.dissipated_damping = header.removed_damping;
          removed_accounts.dissipated_friction = header.removed_friction;
          removed_accounts.work_walls = header.removed_walls;
          removed_accounts.work_fluid = header.removed_fluid;
        }
        dem->resume(header.t, header.steps, root ? header.removed : 0, removed_accounts, std::move(mine),
                    std::move(lists.incoming));
      });
    } else {
      std::vector<int> keep;
      for (size_t i = 0; i < p.size(); ++i)
        if (d.owner_of(p.x[i]) == R.rank) keep.push_back(static_cast<int>(i));
      p.reorder(keep);
    }
  }
  std::unique_ptr<parallel::DistributedDem> dist;
  together(R, "decomposition", false, [&] { dist = std::make_unique<parallel::DistributedDem>(comm, d, *dem); });
  if (root) {
    if (restart)
      fmt::print("restarting from {} at t = {:.6g} s (DEM step {}), written on {} rank(s)\n", info.restart,
                 dem->time(), dem->steps(), header.ranks);
    fmt::print("cgdem {}: {} particles, {} species, {} wall parts, dt = {:g} s, t = {:g} .. {:g} s\n", kGitRevision,
               n_case - header.removed, c.species.size(), dem->scene().parts().size(), c.dem.dt, c.t_start, c.t_end);
    std::string cuts;
    for (int a = 0; a < 3; ++a)
      if (d.dims()[a] > 1) {
        cuts += fmt::format(", {} cut at", "xyz"[a]);
        for (int m = 1; m < d.dims()[a]; ++m) cuts += fmt::format(" {:.4g}", 1e3 * d.cuts()[a][m]);
        cuts += " mm";
      }
    fmt::print("MPI: {} ranks, blocks {} x {} x {} of the domain{}\n", R.size, d.dims()[0],
               d.dims()[1], d.dims()[2], cuts.empty() ? cuts : cuts + " (balanced on the parcels)");
    fmt::print("air: none (vacuum)\n");
    fmt::print("shortest collision time {:.4g} s ({:.1f} steps); set-up {:.2f} s\n", dem->min_collision_time(),
               dem->min_collision_time() / c.dem.dt, setup_clock.seconds());
  }

  std::unique_ptr<io::SnapshotSeries> snapshots;
  std::FILE *energy = nullptr, *diag_csv = nullptr;
  const std::string series_comment = fmt::format("case {}, {} MPI ranks", info.case_file, R.size);
  auto open_csv = [&](const std::string& name, const std::string& hdr) {
    return open_series(c.output.dir, name, hdr, series_comment, restart, dem->time());
  };
  together(R, "output files", true, [&] {
    snapshots = std::make_unique<io::SnapshotSeries>(c.output.dir, "particles", attrs, restart);
    energy = open_csv("energy.csv", energy_csv_header());
    if (diag_spec.enabled) diag_csv = open_csv("diagnostics.csv", diag.csv_header());
  });
  const std::string last_good = (out / "last_good.h5").string();
  const std::string checkpoint = (out / "checkpoint.bin").string();

  // Gathered parcels (rank 0), for the outputs of the same step: their kinematics for the
  // diagnostics, every field for snapshots.
  Particles all;
  long gathered_step = -1;
  bool gathered_all = false;
  auto gather = [&](bool every_field) {
    if (gathered_step == dem->steps() && (gathered_all || !every_field)) return;
    all = every_field ? parallel::gather_particles(comm, dem->particles(), dem->owned())
                      : parallel::gather_kinematics(comm, dem->particles(), dem->owned());
    gathered_step = dem->steps();
    gathered_all = every_field;
  };
  long seen_removed = header.removed, seen_inside = 0;
  auto write_energy = [&] {
    const EnergyBudget e = parallel::global_energy(comm, *dem);
    const long present = sum_over(R, static_cast<long>(dem->owned())), removed = parallel::global_removed(comm, *dem);
    const long inside = sum_over(R, count_inside_walls(dem->scene(), dem->time(), dem->particles(), dem->owned()));
    together(R, "energy.csv", true, [&] {
      if (present + removed != n_case)
        throw RunError(fmt::format("t = {:.6g} s: {} parcels present + {} removed = {} over {} ranks, but the run has "
                                   "{} (a parcel was lost or duplicated)",
                                   dem->time(), present, removed, present + removed, R.size, n_case));
      if (removed > seen_removed)
        fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} more parcel(s) left the domain ({} in all)\n",
                   dem->time(), removed - seen_removed, removed);
      if (inside > seen_inside)
        fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} parcel centre(s) inside a wall (tunnelled)\n",
                   dem->time(), inside);
      seen_removed = removed, seen_inside = inside;
      std::fprintf(energy, "%s\n", energy_csv_row(dem->time(), e, present, removed, inside).c_str());
      std::fflush(energy);
    });
  };
  auto write_diagnostics = [&] {
    if (!diag_spec.enabled) return;
    gather(false);
    together(R, "diagnostics.csv", true, [&] {
      std::fprintf(diag_csv, "%s\n", diag.csv_line(diag.row(dem->time(), all, nullptr, nullptr)).c_str());
      std::fflush(diag_csv);
    });
  };
  auto check_health = [&] {
    together(R, "health check", false,
             [&] { check_particles(dem->particles(), dem->owned(), dem->steps(), dem->time(), c.output.max_speed); });
  };
  auto write_snapshot = [&] {
    gather(true);
    together(R, "snapshot", true, [&] {
      const io::ParticleTable t = to_table(all);
      snapshots->write(dem->steps(), dem->time(), t);
      io::write_particles_h5(last_good, t, attrs);
    });
  };
  auto write_checkpoint_to = [&](const std::string& path) {
    const parallel::PortableState s =
        parallel::gather_state(comm, parallel::portable_state(dem->particles(), dem->neighbor_list(), dem->owned()));
    const EnergyBudget acc = dem->removed_accounts();
    RunHeader h;
    h.t = dem->time(), h.steps = dem->steps(), h.removed = parallel::global_removed(comm, *dem);
    h.builds = dem->neighbor_builds(), h.ranks = R.size;
    h.removed_damping = sum_over(R, acc.dissipated_damping), h.removed_friction = sum_over(R, acc.dissipated_friction);
    h.removed_walls = sum_over(R, acc.work_walls), h.removed_fluid = sum_over(R, acc.work_fluid);
    together(R, "checkpoint", true, [&] { write_portable_checkpoint(path, info.resolved_config, h, s, diag, counters); });
  };
  auto observe = [&](double horizon) {
    if (!diag_spec.enabled) return;
    gather(false);
    if (root) diag.observe(dem->time(), all, horizon);
  };

  check_health();
  if (!restart) {
    observe(0);
    write_energy();
    write_diagnostics();
    write_snapshot();
    write_checkpoint_to(checkpoint);
  }
  PhaseTimers out_timers;
  const int t_observe = out_timers.id("die diagnostics"), t_series = out_timers.id("CSV series");
  const int t_snap = out_timers.id("snapshots"), t_ckpt = out_timers.id("checkpoints");
  OutputSchedule schedule(c, diag_spec, dem->time());  // the same on every rank
  const bool tty = root && isatty(STDOUT_FILENO);
  ProgressLine progress(c, dem->time(), tty);
  const long observe_every = std::max(1L, std::lround(1e-4 / c.dem.dt));
  const long n_present = n_case - header.removed;
  long particle_steps = 0;
  while (!schedule.finished(dem->time())) {
    dem->step();  // its exchanges raise their errors on every rank together
    particle_steps += n_present;  // progress figure only (parcels that leave still count)
    if (dem->steps() % observe_every == 0) {
      auto ts = out_timers.scope(t_observe);
      observe(observe_every * c.dem.dt);
    }
    const double t = dem->time();
    const OutputSchedule::Due due = schedule.after_step(t);
    if (due.energy) {
      auto ts = out_timers.scope(t_series);
      check_health();
      write_energy();
    }
    if (due.diagnostics) {
      auto ts = out_timers.scope(t_series);
      write_diagnostics();
    }
    if (due.snapshot) {
      auto ts = out_timers.scope(t_snap);
      write_snapshot();
    }
    if (due.checkpoint) {
      auto ts = out_timers.scope(t_ckpt);
      check_health();
      write_checkpoint_to(checkpoint);
    }
    if (due.settled) {
      auto ts = out_timers.scope(t_ckpt);
      check_health();
      write_checkpoint_to((out / "settled.bin").string());
      if (root)
        fmt::print("{}settled state at t = {:.6g} s saved: {} (rerun the filling with --restart, on any number of "
                   "ranks)\n",
                   tty ? "\n" : "", t, (out / "settled.bin").string());
    }
    if (root) progress.update(t, particle_steps, due.last);
  }
  if (root) progress.finish();
  const double wall = progress.seconds();
  const EnergyBudget e = parallel::global_energy(comm, *dem);
  const long present = sum_over(R, static_cast<long>(dem->owned())), removed = parallel::global_removed(comm, *dem);
  const long inside = sum_over(R, count_inside_walls(dem->scene(), dem->time(), dem->particles(), dem->owned()));
  const long builds = dem->neighbor_builds();
  const parallel::PortableState final_state =
      parallel::gather_state(comm, parallel::portable_state(dem->particles(), dem->neighbor_list(), dem->owned()));
  // The ranks' own shares of the work, for the balance line.
  const long owned = static_cast<long>(dem->owned());
  long owned_min = owned, owned_max = owned;
  MPI_Allreduce(MPI_IN_PLACE, &owned_min, 1, MPI_LONG, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &owned_max, 1, MPI_LONG, MPI_MAX, comm);
  together(R, "final outputs", true, [&] {
    std::fclose(energy);
    if (diag_csv) std::fclose(diag_csv);
    if (diag_spec.enabled) write_impacts(c.output.dir, diag);
    io::write_metrics((out / "metrics.csv").string(),
                      run_metrics(c.output.dir, dem->time(), present, e, removed, diag_spec.enabled,
                                  diag.front_impact()));
    fmt::print("\n{}", dem->timers().table("per-phase time (DEM, rank 0)"));
    fmt::print("{}", dist->timers().table("inside 'neighbour lists': exchanges (rank 0)"));
    fmt::print("{}", out_timers.table("per-phase time (output, rank 0)"));
    fmt::print("DEM steps {}, wall {:.1f} s, {:.3g} particle-steps/s on {} ranks, neighbour-list builds {}\n",
               dem->steps(), wall, particle_steps / std::max(wall, 1e-9), R.size, builds);
    fmt::print("parcels per rank: {} .. {} (mean {:.0f})\n", owned_min, owned_max, double(present) / R.size);
    fmt::print("particles {} (left the domain: {}, centre inside a wall: {}), solid mass {:.6g} kg\n", present,
               removed, inside, e.mass);
    if (diag_spec.enabled) print_front(diag, diag_spec);
    fmt::print("portable state digest {:016x} at t = {:.9g} s\n", digest(final_state), dem->time());
    fmt::print("outputs in {}: energy.csv, metrics.csv{}, particles.xdmf (+ particles_*.h5), last_good.h5, "
               "checkpoint.bin (portable: restarts on any number of ranks), config.resolved.toml\n",
               c.output.dir, diag_spec.enabled ? ", diagnostics.csv, impacts.csv" : "");
  });
  return 0;
}

}  // namespace cgdem::app

namespace cgdem::app {

int run_distributed_main(int& argc, char**& argv, RunRequest r) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // OpenMP threads call no MPI
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  r.distributed = true;
  int status = 2;
  try {
    status = run_case_file(r);
  } catch (const parallel::RaisedTogether& e) {  // every rank is here: stop cleanly
    if (e.found_here) {
      int size = 1;
      MPI_Comm_size(MPI_COMM_WORLD, &size);
      fmt::print(stderr, "cgdem: error{}: {}\n", size > 1 ? fmt::format(" (rank {})", rank) : "", e.what());
    }
    status = 2;
  } catch (const ConfigError& e) {
    if (rank == 0) fmt::print(stderr, "cgdem: error: {}\n", e.what());
    status = 2;
  } catch (const Error& e) {
    fmt::print(stderr, "cgdem: error (rank {}): {}\n", rank, e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return status;
}

}  // namespace cgdem::app
