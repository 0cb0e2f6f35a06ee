// What a run with parcels writes when (particle_run.cpp, on one process and over MPI
// ranks alike), and how it reports progress.
//
// Output times are multiples of the intervals counted from t_start, also after a restart:
// energy.csv every output.energy_interval (and with every snapshot), shoe_surface.csv every
// diagnostics.surface_interval, a snapshot every output.snapshot_interval, checkpoint.bin
// every output.checkpoint_interval, each at the first step that reaches its time; all of
// them at the last step. A run that starts before the shoe moves (t < 0) saves the state of
// t = 0 once, as settled.bin.
//
// diagnostics.csv is sampled uniformly (its pressures are what `cgdem spectrum` reads): rows
// at t_start + k dT exactly, dT = diagnostics.interval rounded up to a whole multiple that is
// at least the largest step (air.dt_max with air; dT = diagnostics.interval when they agree,
// as in the cases of validation/), so that a step of the usual size ends on every row time.
// A step that ends on a row time (within 1e-3 DEM steps) writes the state at its end; one
// that passes a row time without ending on it (a fluid step shortened by the CFL limit) has
// that row interpolated linearly in time between the states at its start and its end
// (interpolate_row; counts from the nearer one). The steps themselves are never changed. The
// last step writes the final state too, on the grid when time.end is.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "core/timers.hpp"
#include "fluid/fluid_state.hpp"
#include "io/csv_series.hpp"
#include "io/grid_snapshot_series.hpp"
#include "solvers/coupled/coupled_solver.hpp"

namespace cgdem::app {

class OutputSchedule {
 public:
  // t_now: the time the run starts from (t_start, or a checkpoint's time); largest_step: the
  // longest step the run takes (air.dt_max with air, 0: the DEM step).
  OutputSchedule(const DemCase& c, const DiagnosticsSpec& diag, double t_now, double largest_step = 0);
  struct Due {
    bool energy = false, diagnostics = false, surface = false, snapshot = false, checkpoint = false, settled = false, last = false;
    // diagnostics.csv rows the step passed without ending on them (to interpolate), in order;
    // `diagnostics`: a row of the state at the step's end.
    std::vector<double> diagnostics_passed;
  };
  // What is due after a step that ended at time t (the previous one ended at the time of the
  // previous call, or t_now); moves the next times past t.
  Due after_step(double t);
  bool finished(double t) const { return t >= t_end_ - tiny_; }
  // Whether a step from t0 to t1 will pass a diagnostics row time without ending on it (the
  // state at t0 is then needed for the interpolation).
  bool passes_diagnostics(double t0, double t1) const;
  double diagnostics_interval() const { return diag_; }  // dT above [s]
  // The line diagnostics.csv states its sampling with.
  std::string diagnostics_note(double configured_interval) const;

 private:
  double next_after(double interval, double t) const;
  double diag_time(long k) const { return t_start_ + static_cast<double>(k) * diag_; }
  double t_start_, t_end_, tiny_, land_;
  double energy_, snapshot_, checkpoint_, diag_, surface_;  // intervals
  double next_energy_, next_snap_, next_checkpoint_, next_surface_;
  long next_diag_;  // index k of the next row time
  double largest_step_;
  bool with_diag_, settled_pending_;
};

// A diagnostics.csv row at time t between the rows a (earlier) and b (later): every value
// linear in time, the counts (impacts, bubbles) those of the nearer row.
DiagnosticsRow interpolate_row(const DiagnosticsRow& a, const DiagnosticsRow& b, double t);

// The progress line: on a terminal rewritten every 0.5 s, otherwise a plain line every
// output.progress_interval seconds of wall time; always at the last step. The ETA comes
// from this run's own pace (a restart's progress began at t_first, not t_start).
class ProgressLine {
 public:
  ProgressLine(const DemCase& c, double t_first, bool tty);
  void update(double t, long particle_steps, bool last);
  double seconds() const { return clock_.seconds(); }
  void finish() const;  // ends a terminal's line

 private:
  double t_start_, t_end_, t_first_, interval_;
  bool tty_;
  Stopwatch clock_;
  double last_ = 0;
};

// The provenance lines of every CSV a run writes: "cgdem <revision>, <comment>" (comment:
// the case file, the ranks) and where the resolved configuration is.
std::vector<std::string> csv_provenance(const std::string& comment);

// `<dir>/<name>` for a time series (layout of io/csv_series.hpp): on a restart (when it
// exists) kept up to time t and continued, so that it ends as the uninterrupted run's file
// (tests/cli/restart.cmake compares them); otherwise started afresh with the column line,
// the provenance (csv_provenance(comment)) and the column descriptions. Throws cgdem::Error.
// `notes`: more provenance lines (diagnostics.csv: its sampling).
std::unique_ptr<io::CsvSeries> open_series(const std::string& dir, const std::string& name,
                                           const io::CsvColumns& columns, const std::string& comment, bool restart,
                                           double t, const std::vector<std::string>& notes = {});

// impacts.csv of the die-filling diagnostics (written atomically).
void write_impacts(const std::string& dir, const DieDiagnostics& diag, const std::string& comment);

// The closing lines about the die filling: the front's arrival and the impact velocity.
void print_front(const DieDiagnostics& diag, const DiagnosticsSpec& spec);

// Cell-centred air fields for a snapshot of the whole grid: eps, p, the wall fraction alpha
// (alpha_cell may be empty: 0), the velocity averaged onto the cells.
void write_air_snapshot(io::GridSnapshotSeries& series, long step, const fluid::FluidState& air,
                        const fluid::Field& alpha_cell);

// The air's counters of a run (checkpointed with it, run_outputs.hpp).
struct RunCounters {
  long fluid_steps = 0, pressure_iterations = 0, unconverged = 0;
  double max_divergence = 0;        // max |continuity residual| over cells with fluid [1/s]
  double max_divergence_walls = 0;  // the same over cells entirely inside walls (not imposed)
};

// Books a coupled step into the counters; the first unconverged pressure solve is announced
// on stderr (when `announce`: rank 0 of a run over ranks).
void count_fluid_step(RunCounters& c, const CoupledStepStats& st, double t, bool announce = true);
// The counters' line of the final report.
void print_fluid_counters(const RunCounters& c);

// The implicit drag coupling's nonlinear solves (CoupledStepStats::drag).
struct DragCounters {
  long steps = 0, iterations = 0, evaluations = 0;
  int max_iterations = 0;
  double max_residual = 0;  // [m/s] at acceptance
};
void count_drag_step(DragCounters& c, const CoupledStepStats& st);
void print_drag_counters(const DragCounters& c);

// air_steps.csv: what the two counters above sum up, one row per fluid step (the step that
// ended at t), so that a run shows when its pressure or implicit-drag solves struggled. The
// drag columns are there for either coupling, so that the files read alike: without a
// nonlinear solve (semi-implicit) iterations and evaluations are 0 and the residuals nan.
const io::CsvColumns& air_steps_columns();
std::string air_steps_row(double t, const CoupledStepStats& st);

// timings.csv: where the wall-clock time of each run went, in long form: one row per phase
// of the final report's per-phase tables (group dem, coupling, air, output) and three of
// the whole run (group run: wall, the process's set-up before it, other = wall minus the
// four groups), each row carrying what identifies its run (t_s = the simulated time it
// reached, t_start_s, revision, threads, ranks) and that run's counts and peak memory.
// Appended at the end of each run, so that a case run in pieces from checkpoints (one
// output folder, --restart) sums its pieces: group by (group, phase) and add seconds_s. A
// restart from an earlier checkpoint drops the rows of the runs that went beyond it (the
// rule of every time series). Phase names are the tables' names as identifiers
// ("air -> parcels" -> air_to_parcels).
struct RunPiece {
  double t_start = 0, t_end = 0;
  int threads = 1, ranks = 1;
  double wall = 0, set_up = 0;  // s
  long dem_steps = 0, fluid_steps = 0, list_builds = 0, particles = 0;
  double peak_rss_mib = 0;  // the largest over the ranks
};
const io::CsvColumns& timings_columns();
std::string timings_rows(const RunPiece& piece, const std::vector<std::pair<std::string, const PhaseTimers*>>& groups);
// A phase's name as an identifier: lower case, "->" read as "to", every other run of
// characters that are not letters or digits one '_'.
std::string phase_identifier(const std::string& name);

}  // namespace cgdem::app
