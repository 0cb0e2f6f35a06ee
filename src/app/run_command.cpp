#include "app/run_command.hpp"

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/run_case.hpp"
#include "core/config.hpp"

namespace cgdem::app {

int run_case_file(const RunRequest& r) {
  Config cfg = Config::from_file(r.case_file);
  for (const auto& s : r.sets) cfg.apply_override(s);
  if (!r.output.empty()) cfg.apply_override("output.dir=\"" + r.output + "\"");
  DemCase c = read_dem_case(cfg);
  AirCase air = read_air_case(cfg, c.dem);
  DiagnosticsSpec diag = read_diagnostics(cfg);
  cfg.check_unused();
  return run_case(c, air, diag, {r.case_file, cfg.resolved_toml(), r.restart});
}

}  // namespace cgdem::app
