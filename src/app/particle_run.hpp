// `cgdem run` of a case with parcels, in vacuum or with air, on one process or over MPI
// ranks: the phases of the run driver (solvers/run/run_driver.hpp) for such a case. The
// physics is in the solvers (run::ParticleStepper); this decides when to call them and
// what to write (run_outputs.hpp), and prints the banner, the progress and the report.
#pragma once
#include <string>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "solvers/run/domain.hpp"

namespace cgdem::app {

struct RunInfo {
  std::string case_file;
  std::string resolved_config;  // TOML text with defaults filled in
  std::string restart;          // checkpoint to continue from ("" : start afresh)
};

// Collective over the domain's ranks (run::SerialDomain: one process). Returns the exit
// status. Throws cgdem::Error on failures the user must see (over ranks: raised on every
// rank together, parallel::RaisedTogether).
int run_particle_case(run::Domain& domain, const DemCase& c, const AirCase& air, const DiagnosticsSpec& diag,
                      const RunInfo& info);

}  // namespace cgdem::app
