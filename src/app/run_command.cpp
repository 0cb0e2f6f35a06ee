#include "app/run_command.hpp"

#include <fmt/format.h>


#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/flow_case.hpp"
#include "app/run_case.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#ifdef CGDEM_WITH_MPI
#include "app/mpi/run_distributed.hpp"
#endif

namespace cgdem::app {

namespace {

Config load(const RunRequest& r) {
  Config cfg = Config::from_file(r.case_file);
  for (const auto& s : r.sets) cfg.apply_override(s);
  if (!r.output.empty()) cfg.apply_override("output.dir=\"" + r.output + "\"");
  return cfg;
}

}  // namespace

// A case with a [flow] section is a single-phase air case (flow_case.hpp); any other is a
// particle case, with or without air.
int run_case_file(const RunRequest& r) {
  Config cfg = load(r);
  if (is_flow_case(cfg)) {
    if (!r.restart.empty()) throw Error("--restart: flow cases ([flow]) have no checkpoints; run them afresh");
    FlowCase f = read_flow_case(cfg);
    cfg.check_unused();
    return run_flow_case(f, r.case_file, cfg.resolved_toml());
  }
  DemCase c = read_dem_case(cfg);
  AirCase air = read_air_case(cfg, c.dem);
  DiagnosticsSpec diag = read_diagnostics(cfg);
  cfg.check_unused();
  if (air.enabled && diag.enabled) {
    const std::string w = geometry::sliding_plane_warning(diag.die, air.grid.origin.z, air.grid.dx);
    if (!w.empty()) fmt::print(stderr, "cgdem: warning: {}\n", w);
  }
  const RunInfo info{r.case_file, cfg.resolved_toml(), r.restart};
  if (r.distributed) {
#ifdef CGDEM_WITH_MPI
    return run_case_distributed(MPI_COMM_WORLD, c, air, diag, info);
#else
    throw Error("this build of cgdem has no MPI (configured with CGDEM_MPI=OFF or without OpenMPI)");
#endif
  }
  return run_case(c, air, diag, info);
}

// The configuration run_case_file would write to config.resolved.toml (validated, nothing
// run). Used by `cgdem converge --reuse`.
std::string resolve_case_file(const RunRequest& r) {
  Config cfg = load(r);
  if (is_flow_case(cfg)) {
    read_flow_case(cfg);
  } else {
    DemCase c = read_dem_case(cfg);
    read_air_case(cfg, c.dem);
    read_diagnostics(cfg);
  }
  cfg.check_unused();
  return cfg.resolved_toml();
}

}  // namespace cgdem::app
