// What the run loop of `cgdem run` writes when, shared by the single-process run
// (run_case.cpp) and the run over MPI ranks (mpi/run_distributed.cpp), so that both write
// their files at the same times and report progress alike.
//
// Output times are multiples of the intervals counted from t_start, also after a restart:
// energy.csv every output.energy_interval (and with every snapshot), diagnostics.csv every
// diagnostics.interval, shoe_surface.csv every diagnostics.surface_interval, a snapshot every output.snapshot_interval, checkpoint.bin every
// output.checkpoint_interval; all of them at the last step. A run that starts before the
// shoe moves (t < 0) saves the state of t = 0 once, as settled.bin.
#pragma once
#include <cstdio>
#include <string>

#include "app/checkpoint.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "core/timers.hpp"
#include "fluid/fluid_state.hpp"
#include "io/grid_snapshot_series.hpp"
#include "solvers/coupled/coupled_solver.hpp"

namespace cgdem::app {

class OutputSchedule {
 public:
  // t_now: the time the run starts from (t_start, or a checkpoint's time).
  OutputSchedule(const DemCase& c, const DiagnosticsSpec& diag, double t_now);
  struct Due {
    bool energy = false, diagnostics = false, surface = false, snapshot = false, checkpoint = false, settled = false, last = false;
  };
  // What is due after a step that ended at time t; moves the next times past t.
  Due after_step(double t);
  bool finished(double t) const { return t >= t_end_ - tiny_; }

 private:
  double next_after(double interval, double t) const;
  double t_start_, t_end_, tiny_;
  double energy_, snapshot_, checkpoint_, diag_, surface_;  // intervals
  double next_energy_, next_snap_, next_checkpoint_, next_diag_, next_surface_;
  bool with_diag_, settled_pending_;
};

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

// `<dir>/<name>` for a time series: on a restart (when it exists) truncated after t and
// opened to append; otherwise started afresh with a comment line (`comment` after the
// revision, e.g. the case file) and the column header. Throws cgdem::Error.
std::FILE* open_series(const std::string& dir, const std::string& name, const std::string& header,
                       const std::string& comment, bool restart, double t);

// impacts.csv of the die-filling diagnostics (written atomically).
void write_impacts(const std::string& dir, const DieDiagnostics& diag);

// The closing lines about the die filling: the front's arrival and the impact velocity.
void print_front(const DieDiagnostics& diag, const DiagnosticsSpec& spec);

// Cell-centred air fields for a snapshot of the whole grid: eps, p, the wall fraction alpha
// (alpha_cell may be empty: 0), the velocity averaged onto the cells.
void write_air_snapshot(io::GridSnapshotSeries& series, long step, const fluid::FluidState& air,
                        const fluid::Field& alpha_cell);

// Books a coupled step into the counters; the first unconverged pressure solve is announced
// on stderr (when `announce`: rank 0 of a run over ranks).
void count_fluid_step(RunCounters& c, const CoupledStepStats& st, double t, bool announce = true);
// The counters' line of the final report.
void print_fluid_counters(const RunCounters& c);

}  // namespace cgdem::app
