// `cgdem run` for a particle-only (vacuum) case: the outer loop around DemSolver::step —
// output schedule, health checks, progress, the final report. The physics is in the solver.
#pragma once
#include <string>

#include "app/dem_case.hpp"

namespace cgdem::app {

struct RunInfo {
  std::string case_file;
  std::string resolved_config;  // TOML text with defaults filled in
};

// Returns the process exit code. Throws cgdem::Error on failures the user must see.
int run_dem_case(const DemCase& c, const RunInfo& info);

}  // namespace cgdem::app
