// The files a run with parcels writes while it runs (README, "Running cases"): energy.csv,
// diagnostics.csv, shoe_surface.csv, air_steps.csv, the particle and air snapshots,
// last_good.h5 and the checkpoints. Each is written by the same code on one process and over
// N MPI ranks: the ranks give their totals and their parcels (run::RunComm, the identity on
// one process) and rank 0 writes, so that the files read alike however many ranks ran.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/run_schedule.hpp"
#include "io/csv_series.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "solvers/run/particle_stepper.hpp"

namespace cgdem::app {

// What the outputs need to know of the run besides its state.
struct OutputContext {
  std::string case_file;
  std::string resolved_config;  // TOML text with defaults filled in
  bool restart = false;         // the files go on from the checkpoint's time
  std::string diagnostics_note; // how diagnostics.csv is sampled (OutputSchedule::diagnostics_note)
};

class RunOutputs {
 public:
  // Collective. Opens the series (rank 0): afresh, or continued after a restart.
  RunOutputs(run::ParticleStepper& s, const DemCase& c, const DiagnosticsSpec& spec, DieDiagnostics& diag,
             const RunCounters& counters, const OutputContext& ctx);
  ~RunOutputs();

  // Each collective.
  // The die-filling diagnostics' look at the parcels (impacts, mass history); `horizon`:
  // the time to the next look [s].
  void observe(double horizon);
  // energy.csv: a row of the totals. A parcel lost without being counted stops the run;
  // parcels that newly left the domain or entered a wall are announced.
  void energy();
  // Keeps the diagnostics of the state now: the start of a step that will pass a row time.
  void remember_step_start();
  // diagnostics.csv: the rows the step passed (interpolated between its start and its
  // end), then the state at its end when `at_end`.
  void diagnostics(const std::vector<double>& passed, bool at_end);
  void surface();   // shoe_surface.csv: the bed's profile
  void snapshot();  // particles (and air) snapshot, and last_good.h5
  void checkpoint(const std::string& path);
  // air_steps.csv (with air): the row of the fluid step that ended at t. Not collective: rank
  // 0 keeps the rows and writes them when energy.csv is flushed, before a checkpoint (a
  // restart from it finds every row up to its time) and at the end, so that a fluid step
  // costs no file access and no exchange between ranks. The stats are global: the pressure
  // solve's norms and the divergence maxima are reduced over the ranks, and the implicit
  // drag coupling runs on one process.
  void air_step(double t, const CoupledStepStats& st);
  // The end: closes the series, writes impacts.csv and metrics.csv (rank 0).
  void finish(const run::Totals& totals);
  // timings.csv (run_schedule.hpp): this run's rows, on rank 0 (inside together()).
  void timings(const std::string& rows);

  const std::string& series_comment() const { return comment_; }
  // The snapshot field that colours the parcels by where they were at output.tracer_time.
  static constexpr const char* kTracer = "z_start";
  static constexpr const char* kTracerDoc =
      "height of the parcel's centre at the first snapshot at or after output.tracer_time (a tracer)";
  static void save_observers(io::ArchiveWriter& w, const DieDiagnostics& diag, const RunCounters& counters);
  static void load_observers(io::ArchiveReader& r, DieDiagnostics& diag, RunCounters& counters);

 private:
  // The parcels of every rank on rank 0 (one process: its own), gathered once per step.
  const Particles& parcels(run::RunComm::Fields fields);
  DiagnosticsRow diagnostics_now();
  void write_air_steps();  // the kept rows of air_steps.csv, on rank 0 inside together()
  void account_parcels(const run::Totals& t, long inside);
  io::ScalarFields tracer(const io::ParticleTable& t);

  run::ParticleStepper& s_;
  const DemCase& c_;
  const DiagnosticsSpec& spec_;
  DieDiagnostics& diag_;
  const RunCounters& counters_;
  OutputContext ctx_;
  std::string comment_;
  io::Attributes attrs_;
  std::unique_ptr<io::SnapshotSeries> snapshots_;
  std::unique_ptr<io::GridSnapshotSeries> air_snapshots_;
  std::unique_ptr<io::CsvSeries> energy_, diag_csv_, surface_csv_, air_csv_, timings_csv_;
  std::string air_rows_;  // of air_steps.csv, not yet written (rank 0)
  const Particles* gathered_ = nullptr;
  long gathered_step_ = -1;
  run::RunComm::Fields gathered_fields_ = run::RunComm::Fields::Kinematics;
  std::vector<int64_t> tracer_id_;  // ascending ids of the parcels at the tracer time (rank 0)
  std::vector<double> tracer_z_;    // their heights then [m]
  std::optional<DiagnosticsRow> before_;  // at the start of a step that passes a row time
  long n_total_ = 0;                      // parcels present + removed: the run's count
  long seen_removed_ = 0, seen_inside_ = 0;
};

}  // namespace cgdem::app
