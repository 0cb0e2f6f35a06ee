// `cgdem run`: the outer loop around the solvers — DEM alone (vacuum) or the coupled
// DEM-CFD step — with the output schedule, health checks, progress and the final report.
// The physics is in the solvers; this file only decides when to call them and what to write.
#pragma once
#include <string>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"

namespace cgdem::app {

struct RunInfo {
  std::string case_file;
  std::string resolved_config;  // TOML text with defaults filled in
  std::string restart;          // checkpoint to continue from ("" : start afresh)
};

// Returns the process exit code. Throws cgdem::Error on failures the user must see.
int run_case(const DemCase& c, const AirCase& air, const DiagnosticsSpec& diag, const RunInfo& info);

}  // namespace cgdem::app
