#include "app/mpi/run_distributed.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "solvers/pressure_mpi/dist_pressure.hpp"
#include "parallel/mpi/field_gather.hpp"
#include "parallel/mpi/halo_sync.hpp"
#include "solvers/pressure_mpi/pfmg.hpp"
#include "app/checkpoint.hpp"
#include "app/energy_csv.hpp"
#include "app/run_checks.hpp"
#include "app/run_metrics.hpp"
#include "app/run_schedule.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "solvers/dem_mpi/distributed_dem.hpp"
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

// air: the whole grid's state (gathered), or null in vacuum.
void write_portable_checkpoint(const std::string& path, const std::string& config, const RunHeader& h,
                               const parallel::PortableState& s, const DieDiagnostics& diag,
                               const RunCounters& counters, const fluid::FluidState* air) {
  io::ArchiveWriter w;
  w.put(kPortableCheckpointMagic), w.put(kPortableVersion);
  w.put_string(kGitRevision), w.put_string(config);
  w.put<uint8_t>(air != nullptr);
  w.tag("run");
  w.put(h);
  parallel::save(w, s);
  diag.save(w);
  w.tag("counters");
  w.put(counters);
  if (air) put_air(w, *air);
  w.tag("end");
  io::write_file_atomic(path, w.bytes());
}

// air: the whole grid's state to fill (a case with air), or null.
std::string read_portable_checkpoint(const std::string& path, RunHeader& h, parallel::PortableState& s,
                                     DieDiagnostics& diag, RunCounters& counters, fluid::FluidState* air) {
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
  const bool had_air = r.get<uint8_t>() != 0;
  if (had_air != (air != nullptr))
    throw Error(fmt::format("checkpoint {} was written by a run {} air, the case runs {} air", path,
                            had_air ? "with" : "without", air ? "with" : "without"));
  r.tag("run");
  r.get(h);
  parallel::load(r, s);
  diag.load(r);
  r.tag("counters");
  r.get(counters);
  if (air) get_air(r, *air);
  r.tag("end");
  return config;
}

// The block's entries of a field of the whole grid (interior entries, the cut faces included).
void copy_block(const air_mpi::GridBlocks& b, const fluid::Field& whole, fluid::Field& local) {
  const auto e = local.extent();
  const auto lo = b.lo();
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i) local(i, j, k) = whole(i + lo[0], j + lo[1], k + lo[2]);
}

// Cuts of the parcels' blocks moved onto the nearest cell faces of the air grid, so that
// each rank's parcels and air cells are one block: no run shorter than kGhost + 1 cells.
// Returns the run starts of every axis (cells) and rewrites the cuts to match.
air_mpi::GridBlocks::Starts snap_to_cells(parallel::Decomposition::Cuts& cuts, const fluid::MacGrid& g) {
  air_mpi::GridBlocks::Starts starts;
  const int min_run = fluid::kGhost + 1;
  for (int a = 0; a < 3; ++a) {
    const int n = g.n()[a], p = static_cast<int>(cuts[a].size()) - 1;
    if (p > 1 && n < p * min_run)
      throw ConfigError(fmt::format("the air grid has {} cells along {}, too few for {} blocks of at least {} cells",
                                    n, "xyz"[a], p, min_run));
    starts[a] = {0};
    for (int m = 1; m < p; ++m) {
      int c = static_cast<int>(std::lround((cuts[a][m] - g.origin[a]) / g.dx));
      c = std::clamp(c, starts[a].back() + min_run, n - (p - m) * min_run);
      starts[a].push_back(c);
      cuts[a][m] = g.origin[a] + g.dx * c;
    }
    starts[a].push_back(n);
  }
  return starts;
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
  const bool with_air = air_case.enabled;
  if (with_air && air_case.coupled.coupling == DragCoupling::Implicit)
    throw Error("air.coupling = \"implicit\" runs on one process only: the implicit drag coupling over MPI ranks "
                "is not implemented (run without mpirun, or with air.coupling = \"semi-implicit\")");
  const fluid::MacGrid& grid = air_case.grid;
  if (with_air) {
    for (int a = 0; a < 3; ++a)
      if (c.dem.periodic[a])
        throw ConfigError(fmt::format("periodic axes are not supported over MPI ranks (the {} axis is periodic)",
                                      "xyz"[a]));
  }
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
  fluid::FluidState whole_air;   // and its air, on the whole grid
  if (with_air) whole_air = fluid::make_fluid_state(grid);
  std::string stored_config;
  if (restart)
    together(R, "restart", false, [&] {
      stored_config =
          read_portable_checkpoint(info.restart, header, from, diag, counters, with_air ? &whole_air : nullptr);
    });
  for (const Vec3& x : restart ? from.p.x : dem->particles().x) where.push_back(x);
  Vec3 lo = box.hi, hi = box.lo;
  for (const Vec3& x : where) lo = cmin(lo, x), hi = cmax(hi, x);
  Vec3 extent;
  for (int a = 0; a < 3; ++a) extent[a] = std::max(hi[a] - lo[a], 0.0) + range;
  // With air the cuts then move onto cell faces: one block of parcels and cells per rank.
  parallel::Decomposition::Cuts cuts;
  for (int a = 0; a < 3; ++a) cuts[a] = {box.lo[a], box.hi[a]};
  air_mpi::GridBlocks::Starts starts;
  together(R, "decomposition", false, [&] {
    // With air, a cell of margin: moving a cut onto a cell face may narrow a block by dx/2.
    if (R.size > 1)
      cuts = parallel::balanced_cuts(box, parallel::choose_dims(R.size, extent), where,
                                     with_air ? range + grid.dx : range);
    if (!with_air) return;
    starts = snap_to_cells(cuts, grid);
    if (R.size > 1 && !(dem->params().skin < grid.dx))
      throw ConfigError(fmt::format(
          "over MPI ranks a parcel may stray half the neighbour-list skin ({:g} m) beyond its block between list "
          "builds, and its coupling kernel must stay within the {} ghost layers of air cells: the skin must be "
          "shorter than the cell size air.dx = {:g} m",
          dem->params().skin, fluid::kGhost, grid.dx));
  });
  const parallel::Decomposition d(box, cuts);
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
  // The air of this rank's block: grid, boundary (cut sides marked), the distributed
  // pressure solve, the coupling, all through one HaloSync.
  std::unique_ptr<air_mpi::GridBlocks> blocks;
  std::unique_ptr<air_mpi::HaloSync> sync;
  fluid::FluidState air;
  std::unique_ptr<fluid::FluidSolver> fluid;
  std::unique_ptr<CoupledSolver> coupled;
  std::string preconditioner = air_case.mpi_preconditioner;
  // "auto": additive Schwarz multigrid on a few ranks (4 ms of Case 1-3 on 2 ranks: 30.9 PCG
  // iterations and 5.4 s of solves per 20 fluid steps; bj-mg 62.0 and 6.8 s, pfmg 51.1 and
  // 12.7 s), hypre's PFMG beyond (its iterations do not grow with the rank count;
  // docs/scale_out.md).
  if (preconditioner == "auto") preconditioner = R.size <= 4 || !air_mpi::have_pfmg() ? "as-mg2" : "pfmg";
  if (with_air) {
    together(R, "air set-up", false, [&] {
      blocks = std::make_unique<air_mpi::GridBlocks>(grid.n(), starts, R.rank);
      if (blocks->dims() != d.dims()) throw Error("air blocks and parcel blocks disagree (internal)");
    });
    sync = std::make_unique<air_mpi::HaloSync>(comm, *blocks, grid, air_case.fluid.bc);
    fluid::FluidParams local = air_case.fluid;
    local.bc = sync->local_bc();
    air_mpi::DistOptions opt;
    opt.preconditioner = preconditioner;
    opt.rel_tol = air_case.fluid.pressure.rel_tol;
    opt.max_iter = air_case.fluid.pressure.max_iter;
    together(R, "air set-up", false, [&] {
      auto ps = std::make_unique<air_mpi::DistPressureSolver>(comm, *blocks, fluid::pressure_grid(grid, air_case.fluid),
                                                              opt);
      fluid = std::make_unique<fluid::FluidSolver>(sync->local_grid(), local, std::move(ps));
    });
    fluid->set_sync(*sync);
    air = fluid::make_fluid_state(sync->local_grid());
    coupling::ExchangeParams xp = air_case.exchange;
    xp.bc = sync->local_bc();
    coupling::Exchange exchange(sync->local_grid(), c.species, xp);
    exchange.set_sync(sync.get());
    coupled = std::make_unique<CoupledSolver>(*dem, *fluid, air, std::move(exchange), air_case.coupled);
    if (restart) {  // the checkpoint's air on this block, ghosts from the boundaries and the neighbours
      air.t = whole_air.t;
      for (int q = 0; q < 3; ++q) copy_block(*blocks, whole_air.vel(q), air.vel(q));
      copy_block(*blocks, whole_air.p, air.p);
      copy_block(*blocks, whole_air.eps, air.eps);
      copy_block(*blocks, whole_air.eps_old, air.eps_old);
      sync->fill_velocity(air.u, air.v, air.w);
      sync->fill_scalar(air.p, fluid::ScalarKind::Pressure);
      sync->fill_scalar(air.eps, fluid::ScalarKind::ZeroGradient);
      sync->fill_scalar(air.eps_old, fluid::ScalarKind::ZeroGradient);
    }
    whole_air = {};
  }
  if (root) {
    if (restart)
      fmt::print("restarting from {} at t = {:.6g} s (DEM step {}), written on {} rank(s)\n", info.restart,
                 dem->time(), dem->steps(), header.ranks);
    fmt::print("cgdem {}: {} particles, {} species, {} wall parts, dt = {:g} s, t = {:g} .. {:g} s\n", kGitRevision,
               n_case - header.removed, c.species.size(), dem->scene().parts().size(), c.dem.dt, c.t_start, c.t_end);
    std::string cut_text;
    for (int a = 0; a < 3; ++a)
      if (d.dims()[a] > 1) {
        cut_text += fmt::format(", {} cut at", "xyz"[a]);
        for (int m = 1; m < d.dims()[a]; ++m) cut_text += fmt::format(" {:.4g}", 1e3 * d.cuts()[a][m]);
        cut_text += " mm";
      }
    fmt::print("MPI: {} ranks, blocks {} x {} x {} of the domain{}\n", R.size, d.dims()[0], d.dims()[1],
               d.dims()[2],
               cut_text.empty() ? cut_text
                                : cut_text + (with_air ? " (balanced on the parcels, on cell faces)" : " (balanced on the parcels)"));
    if (with_air)
      fmt::print("air: {} x {} x {} cells of {:g} m, fluid step <= {:g} s, pressure: distributed PCG + {} (tol {:g}), "
                 "{}-way coupling\n",
                 grid.nx, grid.ny, grid.nz, grid.dx, air_case.coupled.dt_fluid_max, preconditioner,
                 air_case.fluid.pressure.rel_tol, air_case.coupled.feedback ? "two" : "one");
    else
      fmt::print("air: none (vacuum)\n");
    fmt::print("shortest collision time {:.4g} s ({:.1f} steps); set-up {:.2f} s\n", dem->min_collision_time(),
               dem->min_collision_time() / c.dem.dt, setup_clock.seconds());
  }

  std::unique_ptr<io::SnapshotSeries> snapshots;
  std::unique_ptr<io::GridSnapshotSeries> air_snapshots;
  std::unique_ptr<io::CsvSeries> energy, diag_csv, surface_csv;
  const std::string series_comment = fmt::format("case {}, {} MPI ranks", info.case_file, R.size);
  auto open_csv = [&](const std::string& name, const io::CsvColumns& columns) {
    return open_series(c.output.dir, name, columns, series_comment, restart, dem->time());
  };
  together(R, "output files", true, [&] {
    snapshots =
        std::make_unique<io::SnapshotSeries>(c.output.dir, "particles", attrs, restart, c.output.compression);
    if (with_air) air_snapshots = std::make_unique<io::GridSnapshotSeries>(c.output.dir, "air", attrs, restart,
                                                                          c.output.compression);
    energy = open_csv("energy.csv", energy_csv_columns());
    if (diag_spec.enabled) diag_csv = open_csv("diagnostics.csv", diag.csv_columns());
    if (diag_spec.enabled) surface_csv = open_csv("shoe_surface.csv", diag.surface_columns());
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
    EnergyBudget e = parallel::global_energy(comm, *dem);
    if (with_air) e.work_fluid = sum_over(R, dem->fluid_work());
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
      energy->row(energy_csv_row(dem->time(), e, present, removed, inside));
      energy->flush();
    });
  };
  auto write_diagnostics = [&] {
    if (!diag_spec.enabled) return;
    gather(false);
    // The pressure cells: this block's sums, added over the ranks.
    std::vector<DieDiagnostics::PressureSum> sums;
    PathFlux paths;
    if (with_air) {
      sums = diag.pressure_sums(air, grid, air_case.fluid);
      paths = diag.path_fluxes(air, dem->time());
      std::vector<double> v;
      for (const auto& q : sums) v.push_back(q.sum), v.push_back(double(q.cells));
      v.push_back(paths.cavity), v.push_back(paths.walls), v.push_back(paths.open);
      parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm),
                          "MPI_Allreduce", "pressure cells and air paths");
      for (size_t q = 0; q < sums.size(); ++q) sums[q].sum = v[2 * q], sums[q].cells = std::lround(v[2 * q + 1]);
      paths = {v[2 * sums.size()], v[2 * sums.size() + 1], v[2 * sums.size() + 2]};
    }
    together(R, "diagnostics.csv", true, [&] {
      DiagnosticsRow row = diag.row(dem->time(), all, nullptr, nullptr);
      if (with_air) {  // the bubble census needs the whole grid: not over ranks (NaN)
        row.pressure = diag.mean_pressures(sums);
        row.q_cavity = paths.cavity, row.q_walls = paths.walls, row.q_open = paths.open;
      }
      diag_csv->row(diag.csv_line(row));
      diag_csv->flush();
    });
  };
  auto write_surface = [&] {
    if (!diag_spec.enabled) return;
    gather(false);
    together(R, "shoe_surface.csv", true, [&] {
      surface_csv->rows(diag.surface_rows(dem->time(), all));
      surface_csv->flush();
    });
  };
  auto check_health = [&] {
    together(R, "health check", false, [&] {
      check_particles(dem->particles(), dem->owned(), dem->steps(), dem->time(), c.output.max_speed);
      if (with_air) check_air(air, c.output.max_speed, counters.fluid_steps, blocks->lo());
    });
  };
  // The air of the whole grid on rank 0 (collective), for snapshots and checkpoints.
  auto gather_air = [&](fluid::Field* alpha) {
    fluid::FluidState whole;
    whole.grid = grid;
    whole.t = air.t;
    for (int q = 0; q < 3; ++q) whole.vel(q) = air_mpi::gather_field(comm, *blocks, air.vel(q), q);
    whole.p = air_mpi::gather_field(comm, *blocks, air.p, air_mpi::kCellCentred);
    whole.eps = air_mpi::gather_field(comm, *blocks, air.eps, air_mpi::kCellCentred);
    whole.eps_old = air_mpi::gather_field(comm, *blocks, air.eps_old, air_mpi::kCellCentred);
    if (alpha) {
      const fluid::Field& a = fluid->ibm().alpha_cell;
      *alpha = air_mpi::gather_field(comm, *blocks, a.empty() ? fluid::make_cell_field(air.grid) : a,
                                     air_mpi::kCellCentred);
    }
    return whole;
  };
  auto write_snapshot = [&] {
    gather(true);
    fluid::Field alpha;
    const fluid::FluidState whole = with_air ? gather_air(&alpha) : fluid::FluidState{};
    together(R, "snapshot", true, [&] {
      const io::ParticleTable t = to_table(all);
      snapshots->write(dem->steps(), dem->time(), t);
      if (with_air) write_air_snapshot(*air_snapshots, dem->steps(), whole, alpha);
      io::write_particles_h5(last_good, t, attrs, c.output.compression,
                             io::Instant{dem->time(), dem->steps()});
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
    const fluid::FluidState whole = with_air ? gather_air(nullptr) : fluid::FluidState{};
    together(R, "checkpoint", true, [&] {
      write_portable_checkpoint(path, info.resolved_config, h, s, diag, counters, with_air ? &whole : nullptr);
    });
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
    write_surface();
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
    if (with_air) {  // its exchanges and reductions raise their errors on every rank together
      const CoupledStepStats st = coupled->step();
      particle_steps += st.substeps * n_present;
      count_fluid_step(counters, st, dem->time(), root);  // global figures, the same on every rank
      auto ts = out_timers.scope(t_observe);
      observe(st.dt_fluid);  // the next step: as long as this one
    } else {
      dem->step();  // its exchanges raise their errors on every rank together
      particle_steps += n_present;  // progress figure only (parcels that leave still count)
      if (dem->steps() % observe_every == 0) {
        auto ts = out_timers.scope(t_observe);
        observe(observe_every * c.dem.dt);
      }
    }
    const double t = dem->time();
    const OutputSchedule::Due due = schedule.after_step(t);
    if (due.energy) {
      auto ts = out_timers.scope(t_series);
      check_health();
      write_energy();
    }
    if (due.diagnostics || !due.diagnostics_passed.empty()) {  // over ranks: at the step's end, not interpolated
      auto ts = out_timers.scope(t_series);
      write_diagnostics();
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
  EnergyBudget e = parallel::global_energy(comm, *dem);
  if (with_air) e.work_fluid = sum_over(R, dem->fluid_work());
  const long present = sum_over(R, static_cast<long>(dem->owned())), removed = parallel::global_removed(comm, *dem);
  const long inside = sum_over(R, count_inside_walls(dem->scene(), dem->time(), dem->particles(), dem->owned()));
  const long builds = dem->neighbor_builds();
  const long cells = with_air ? blocks->local_count() : 0;
  long cells_min = cells, cells_max = cells;
  MPI_Allreduce(MPI_IN_PLACE, &cells_min, 1, MPI_LONG, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &cells_max, 1, MPI_LONG, MPI_MAX, comm);
  const parallel::PortableState final_state =
      parallel::gather_state(comm, parallel::portable_state(dem->particles(), dem->neighbor_list(), dem->owned()));
  // The ranks' own shares of the work, for the balance line.
  const long owned = static_cast<long>(dem->owned());
  long owned_min = owned, owned_max = owned;
  MPI_Allreduce(MPI_IN_PLACE, &owned_min, 1, MPI_LONG, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &owned_max, 1, MPI_LONG, MPI_MAX, comm);
  together(R, "final outputs", true, [&] {
    energy.reset(), diag_csv.reset(), surface_csv.reset();
    if (diag_spec.enabled) write_impacts(c.output.dir, diag, series_comment);
    io::write_metrics((out / "metrics.csv").string(),
                      run_metrics(c.output.dir, dem->time(), present, e, removed, diag_spec.enabled,
                                  diag.front_impact(), DieRun{diag_spec.die, with_air}));
    fmt::print("\n{}", dem->timers().table("per-phase time (DEM, rank 0)"));
    fmt::print("{}", dist->timers().table("inside 'neighbour lists': exchanges (rank 0)"));
    if (with_air) {
      fmt::print("{}", coupled->timers().table("per-phase time (coupling, rank 0)"));
      fmt::print("{}", fluid->timers().table("per-phase time (air, rank 0)"));
      print_fluid_counters(counters);
      fmt::print("air cells per rank: {} .. {}\n", cells_min, cells_max);
    }
    fmt::print("{}", out_timers.table("per-phase time (output, rank 0)"));
    fmt::print("DEM steps {}, wall {:.1f} s, {:.3g} particle-steps/s on {} ranks, neighbour-list builds {}\n",
               dem->steps(), wall, particle_steps / std::max(wall, 1e-9), R.size, builds);
    fmt::print("parcels per rank: {} .. {} (mean {:.0f})\n", owned_min, owned_max, double(present) / R.size);
    fmt::print("particles {} (left the domain: {}, centre inside a wall: {}), solid mass {:.6g} kg\n", present,
               removed, inside, e.mass);
    if (diag_spec.enabled) print_front(diag, diag_spec);
    fmt::print("portable state digest {:016x} at t = {:.9g} s\n", digest(final_state), dem->time());
    fmt::print("outputs in {}: energy.csv, metrics.csv{}, particles.xdmf (+ particles_*.h5){}, last_good.h5, "
               "checkpoint.bin (portable: restarts on any number of ranks), config.resolved.toml\n",
               c.output.dir, diag_spec.enabled ? ", diagnostics.csv, impacts.csv" : "",
               with_air ? ", air.xdmf (+ air_*.h5)" : "");
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
