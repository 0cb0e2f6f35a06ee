#include "solvers/run/run_driver.hpp"

namespace cgdem::run {

int drive(Run& run) {
  const bool restart = run.set_up();
  run.check_health();
  if (!restart) run.write_initial();
  while (!run.finished()) {
    run.step();
    run.observe();
    const Due due = run.due();
    if (due.health) run.check_health();
    run.write_due();
    run.progress(due.last);
  }
  return run.report();
}

}  // namespace cgdem::run
