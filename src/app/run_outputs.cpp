#include "app/run_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/energy_csv.hpp"
#include "app/run_checks.hpp"
#include "app/run_metrics.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/h5_util.hpp"
#include "io/xdmf_series.hpp"
#include "particles/particle_io.hpp"
#include "solvers/run/run_checkpoint.hpp"

namespace cgdem::app {

namespace {

std::string in_folder(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).string();
}

// The tracer of the newest snapshot of `dir` at or before `step` that carries one (ids and
// heights in id order); empty when none does.
void read_tracer(const io::SnapshotSeries& series, const std::string& dir, int64_t step, std::vector<int64_t>& ids,
                 std::vector<double>& z) {
  ids.clear(), z.clear();
  std::vector<int64_t> steps = io::find_snapshot_steps(dir, "particles");
  for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
    if (*it > step) continue;
    const std::string path = series.snapshot_path(*it);
    io::h5::Quiet quiet;
    io::h5::Id file = io::h5::open_file(path);
    if (!io::h5::exists(file, "fields/" + std::string(RunOutputs::kTracer))) continue;
    std::vector<hsize_t> dims;
    ids = io::h5::read_int64(file, "particles/id", dims, path);
    z = io::h5::read_double(file, "fields/" + std::string(RunOutputs::kTracer), dims, path);
    if (ids.size() != z.size()) throw Error(path + ": the tracer has " + std::to_string(z.size()) + " values for " +
                                            std::to_string(ids.size()) + " parcels");
    return;
  }
}

}  // namespace

RunOutputs::RunOutputs(run::ParticleStepper& s, const DemCase& c, const DiagnosticsSpec& spec, DieDiagnostics& diag,
                       const RunCounters& counters, const OutputContext& ctx)
    : s_(s), c_(c), spec_(spec), diag_(diag), counters_(counters), ctx_(ctx) {
  run::RunComm& comm = s_.comm();
  const bool ranks = comm.size() > 1;
  comment_ = "case " + ctx_.case_file + (ranks ? fmt::format(", {} MPI ranks", comm.size()) : "");
  attrs_ = {{"cgdem_revision", kGitRevision}, {"config", ctx_.resolved_config}};
  if (ranks) attrs_["mpi_ranks"] = std::to_string(comm.size());
  const run::Totals t = s_.totals();
  n_total_ = t.present + t.removed;
  seen_removed_ = t.removed;
  const double now = s_.dem().time();
  const std::string& dir = c_.output.dir;
  // Time series: on a restart the rows after the checkpoint's time are dropped and the file
  // continues; otherwise it starts afresh.
  auto open_csv = [&](const std::string& name, const io::CsvColumns& columns, std::vector<std::string> notes = {}) {
    return open_series(dir, name, columns, comment_, ctx_.restart, now, notes);
  };
  comm.together("output files", true, [&] {
    snapshots_ = std::make_unique<io::SnapshotSeries>(dir, "particles", attrs_, ctx_.restart, c_.output.compression);
    if (s_.with_air())
      air_snapshots_ =
          std::make_unique<io::GridSnapshotSeries>(dir, "air", attrs_, ctx_.restart, c_.output.compression);
    energy_ = open_csv("energy.csv", energy_csv_columns(c_.dem.accounts),
                       c_.dem.accounts ? std::vector<std::string>{} : std::vector{energy_csv_accounts_note()});
    if (spec_.enabled) diag_csv_ = open_csv("diagnostics.csv", diag_.csv_columns(), {ctx_.diagnostics_note});
    if (spec_.enabled) surface_csv_ = open_csv("shoe_surface.csv", diag_.surface_columns());
    if (s_.with_air()) air_csv_ = open_csv("air_steps.csv", air_steps_columns());
    timings_csv_ = open_csv("timings.csv", timings_columns());
    // A restart after the tracer was taken continues with the one its snapshots carry.
    if (ctx_.restart) read_tracer(*snapshots_, dir, s_.dem().steps(), tracer_id_, tracer_z_);
  });
}

// A run stopped by an error (a drag solve that did not converge, a failed health check)
// still leaves the rows of its last steps: they show how it came to stop.
RunOutputs::~RunOutputs() {
  if (!air_csv_ || air_rows_.empty()) return;
  try {
    air_csv_->rows(air_rows_);
  } catch (...) {  // the run is already stopping with its own error
  }
}

const Particles& RunOutputs::parcels(run::RunComm::Fields fields) {
  using F = run::RunComm::Fields;
  const DemSolver& dem = s_.dem();
  if (gathered_ && gathered_step_ == dem.steps() && (gathered_fields_ == F::All || fields == F::Kinematics))
    return *gathered_;
  gathered_ = &s_.comm().gather(dem.particles(), dem.owned(), fields);
  gathered_step_ = dem.steps(), gathered_fields_ = fields;
  return *gathered_;
}

void RunOutputs::observe(double horizon) {
  if (!spec_.enabled) return;
  const DemSolver& dem = s_.dem();
  const Particles& all = parcels(run::RunComm::Fields::Kinematics);
  if (s_.comm().root()) diag_.observe(dem.time(), all, horizon);
}

void RunOutputs::energy() {
  const DemSolver& dem = s_.dem();
  const run::Totals t = s_.totals();
  const long inside = s_.comm().sum(count_inside_walls(dem.scene(), dem.time(), dem.particles(), dem.owned()));
  s_.comm().together("energy.csv", true, [&] {
    account_parcels(t, inside);
    energy_->row(energy_csv_row(dem.time(), t.energy, t.present, t.removed, inside));
    energy_->flush();
    write_air_steps();
  });
}

void RunOutputs::air_step(double t, const CoupledStepStats& st) {
  if (air_csv_) air_rows_ += air_steps_row(t, st) + "\n";
}

void RunOutputs::write_air_steps() {
  if (!air_csv_) return;
  air_csv_->rows(air_rows_);
  air_rows_.clear();
  air_csv_->flush();
}

// Parcels are never lost silently: the count (present + removed) must stay what it was,
// and every new departure or tunnelling is announced when it is seen.
void RunOutputs::account_parcels(const run::Totals& t, long inside) {
  const double now = s_.dem().time();
  const int ranks = s_.comm().size();
  if (t.present + t.removed != n_total_)
    throw RunError(fmt::format("t = {:.6g} s: {} parcels present + {} removed = {}{}, but the run has {} (a parcel "
                               "was lost without being counted, or counted twice)",
                               now, t.present, t.removed, t.present + t.removed,
                               ranks > 1 ? fmt::format(" over {} ranks", ranks) : "", n_total_));
  if (t.removed > seen_removed_)
    fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} more parcel(s) left the domain ({} in all)\n", now,
               t.removed - seen_removed_, t.removed);
  if (inside > seen_inside_)
    fmt::print(stderr, "cgdem: warning: t = {:.6g} s: {} parcel centre(s) inside a wall (tunnelled)\n", now, inside);
  seen_removed_ = t.removed;
  seen_inside_ = inside;
}

// The row of the state now: the parcels' part from the gathered parcels, the air's from
// the sums of every rank's cells (pressure cells, paths out of the die). The bubble census
// needs the whole grid: on one process only (NaN over ranks).
DiagnosticsRow RunOutputs::diagnostics_now() {
  const DemSolver& dem = s_.dem();
  run::RunComm& comm = s_.comm();
  const Particles& all = parcels(run::RunComm::Fields::Kinematics);
  std::vector<DieDiagnostics::PressureSum> sums;
  PathFlux paths;
  if (s_.with_air()) {
    const fluid::FluidParams& fp = s_.air_spec().fluid;
    sums = diag_.pressure_sums(s_.air(), s_.air_spec().grid, fp);
    paths = diag_.path_fluxes(s_.air(), dem.time());
    std::vector<double> v;
    for (const auto& q : sums) v.push_back(q.sum), v.push_back(double(q.cells));
    v.push_back(paths.cavity), v.push_back(paths.walls), v.push_back(paths.open);
    comm.sum(v);
    for (size_t q = 0; q < sums.size(); ++q) sums[q].sum = v[2 * q], sums[q].cells = std::lround(v[2 * q + 1]);
    paths = {v[2 * sums.size()], v[2 * sums.size() + 1], v[2 * sums.size() + 2]};
  }
  DiagnosticsRow row;
  comm.together("diagnostics.csv", true, [&] {
    row = diag_.row(dem.time(), all, nullptr, nullptr);
    if (!s_.with_air()) return;
    row.pressure = diag_.mean_pressures(sums);
    row.q_cavity = paths.cavity, row.q_walls = paths.walls, row.q_open = paths.open;
    if (comm.size() == 1) diag_.count_bubbles(row, s_.air(), s_.fluid().ibm().alpha_cell, s_.air_spec().fluid);
  });
  return row;
}

void RunOutputs::remember_step_start() { before_ = diagnostics_now(); }

void RunOutputs::diagnostics(const std::vector<double>& passed, bool at_end) {
  if (!spec_.enabled) return;
  const DiagnosticsRow now = diagnostics_now();
  s_.comm().together("diagnostics.csv", true, [&] {
    for (double tk : passed) diag_csv_->row(diag_.csv_line(before_ ? interpolate_row(*before_, now, tk) : now));
    if (at_end) diag_csv_->row(diag_.csv_line(now));
    diag_csv_->flush();
  });
  before_.reset();
}

void RunOutputs::surface() {
  if (!spec_.enabled) return;
  const DemSolver& dem = s_.dem();
  const Particles& all = parcels(run::RunComm::Fields::Kinematics);
  s_.comm().together("shoe_surface.csv", true, [&] {
    surface_csv_->rows(diag_.surface_rows(dem.time(), all));
    surface_csv_->flush();
  });
}

void RunOutputs::snapshot() {
  const DemSolver& dem = s_.dem();
  const Particles& all = parcels(run::RunComm::Fields::All);
  const fluid::FluidState* air = s_.with_air() ? &s_.whole_air() : nullptr;
  const fluid::Field* alpha = s_.with_air() ? &s_.whole_alpha() : nullptr;
  s_.comm().together("snapshot", true, [&] {
    const io::ParticleTable t = to_table(all);
    snapshots_->write(dem.steps(), dem.time(), t, tracer(t), {{kTracer, {"m", kTracerDoc}}});
    if (air) write_air_snapshot(*air_snapshots_, dem.steps(), *air, *alpha);
    // atomic: always a consistent state
    io::write_particles_h5(in_folder(c_.output.dir, "last_good.h5"), t, attrs_, c_.output.compression,
                           io::Instant{dem.time(), dem.steps()});
  });
}

// The tracer z_start of the table's parcels (in id order, as to_table gives them): taken
// from the parcels' heights at the first snapshot at or after output.tracer_time, carried
// from then on; before then, no field.
io::ScalarFields RunOutputs::tracer(const io::ParticleTable& t) {
  if (tracer_id_.empty()) {
    const double tt = c_.output.tracer_time;  // with a slack for the round-off of the snapshot times
    if (s_.dem().time() < tt - 1e-12 * std::max(1.0, std::fabs(tt))) return {};
    tracer_id_ = t.id;
    tracer_z_.resize(t.size());
    for (size_t i = 0; i < t.size(); ++i) tracer_z_[i] = t.x[i].z;
  }
  std::vector<double> z(t.size());
  size_t q = 0;  // both lists ascend in id; parcels are only ever removed
  for (size_t i = 0; i < t.size(); ++i) {
    while (q < tracer_id_.size() && tracer_id_[q] < t.id[i]) ++q;
    if (q == tracer_id_.size() || tracer_id_[q] != t.id[i])
      throw RunError(fmt::format("t = {:.6g} s: parcel {} has no tracer (it was not present at the tracer time "
                                 "output.tracer_time = {:g} s)",
                                 s_.dem().time(), t.id[i], c_.output.tracer_time));
    z[i] = tracer_z_[q];
  }
  return {{kTracer, std::move(z)}};
}

void RunOutputs::checkpoint(const std::string& path) {
  if (s_.with_air()) s_.comm().together("air_steps.csv", true, [&] { write_air_steps(); });
  run::write_checkpoint(path, ctx_.resolved_config, s_,
                        [&](io::ArchiveWriter& w) { save_observers(w, diag_, counters_); });
}

void RunOutputs::finish(const run::Totals& totals) {
  s_.comm().together("final outputs", true, [&] {
    write_air_steps();
    energy_.reset(), diag_csv_.reset(), surface_csv_.reset(), air_csv_.reset();
    if (spec_.enabled) write_impacts(c_.output.dir, diag_, comment_);
    io::write_metrics(in_folder(c_.output.dir, "metrics.csv"),
                      run_metrics(c_.output.dir, s_.dem().time(), totals.present, totals.energy, totals.removed,
                                  spec_.enabled, diag_.front_impact(), DieRun{spec_.die, s_.with_air()}));
  });
}

void RunOutputs::timings(const std::string& rows) {
  timings_csv_->rows(rows);
  timings_csv_->flush();
}

void RunOutputs::save_observers(io::ArchiveWriter& w, const DieDiagnostics& diag, const RunCounters& counters) {
  diag.save(w);
  w.tag("counters");
  w.put(counters);
}

void RunOutputs::load_observers(io::ArchiveReader& r, DieDiagnostics& diag, RunCounters& counters) {
  diag.load(r);
  r.tag("counters");
  r.get(counters);
}

}  // namespace cgdem::app
