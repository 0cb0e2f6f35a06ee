// The run driver of `cgdem run`: the one sequence every run follows, whatever it steps
// (parcels with or without air, or the air alone) and on however many MPI ranks:
//
//   set_up                   build the solvers; for a restart, put them in the checkpoint's
//                            state (its files then go on where they stopped)
//   check_health
//   write_initial            the starting state's outputs (a fresh run only)
//   until finished:
//     step                   one step of what advances time
//     observe                what watches every step (impacts, the mass history)
//     due                    what the step made due (the run's schedule decides)
//     check_health           when due: no NaN, no runaway speed, before anything is written
//     write_due              the outputs that are due
//     progress
//   report                   the final files and the closing lines; the exit status
//
// A Run supplies the phases; drive() puts them in this order and nothing else. Over MPI
// ranks every phase is collective (the ranks call it together, and an error found on one
// rank stops every rank at the same point: RunComm::together).
#pragma once

namespace cgdem::run {

// What the step just taken made due.
struct Due {
  bool health = false;  // check the state before the outputs
  bool last = false;    // the run's last step
};

class Run {
 public:
  virtual ~Run() = default;
  // Returns true for a restart (the starting state's outputs were written by the run that
  // wrote the checkpoint).
  virtual bool set_up() = 0;
  virtual void check_health() = 0;
  virtual void write_initial() = 0;
  virtual bool finished() const = 0;
  virtual void step() = 0;
  virtual void observe() = 0;
  virtual Due due() = 0;
  virtual void write_due() = 0;
  virtual void progress(bool last) = 0;
  virtual int report() = 0;
};

// Runs `run` from set-up to report. Returns the exit status report() gives.
int drive(Run& run);

}  // namespace cgdem::run
