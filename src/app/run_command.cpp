#include "app/run_command.hpp"

#include <fmt/format.h>

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <regex>
#include <system_error>

#include "app/air_case.hpp"
#include "app/case_keys.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/flow_case.hpp"
#include "app/particle_run.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "solvers/run/domain.hpp"
#ifdef CGDEM_WITH_MPI
#include "solvers/run_mpi/mpi_domain.hpp"
#endif

namespace cgdem::app {

namespace {

Config load(const RunRequest& r) {
  Config cfg = Config::from_file(r.case_file);
  for (const auto& s : r.sets) cfg.apply_override(s);
  if (!r.output.empty()) cfg.override_string("output.dir", r.output, fmt::format("--output '{}'", r.output));
  return cfg;
}

// The output folder, created before anything is written to it: a folder that cannot be
// made (a parent that is a file, a read-only file system, no permission) stops the run
// with its name and the reason.
void make_output_folder(Config& cfg, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir, ec))
    throw Error(fmt::format("cannot create the output folder '{}' (output.dir, from {}): {}", dir,
                            cfg.origin("output.dir"), ec ? ec.message() : "not a folder"));
}

// Temporaries `<file>.tmp-<pid>` (io/atomic_file.hpp) of a process that no longer exists
// were left by a run that was killed while writing: removed, and said so. The files they
// were to replace are complete (the previous version) or absent.
void remove_stale_temporaries(const std::string& dir) {
  static const std::regex tmp_re(R"(.*\.tmp-([0-9]{1,9}))");
  std::vector<std::string> removed;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    std::smatch m;
    if (!e.is_regular_file(ec) || !std::regex_match(name, m, tmp_re)) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(m[1].str()));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    if (std::filesystem::remove(e.path(), ec)) removed.push_back(name);
  }
  if (!removed.empty())
    fmt::print(stderr, "cgdem: removed {} temporary file(s) left in {} by an interrupted run: {}\n", removed.size(), dir,
               fmt::join(removed, ", "));
}

std::string case_folder(const std::string& case_file) {
  const std::string d = std::filesystem::path(case_file).parent_path().string();
  return d.empty() ? "." : d;
}

}  // namespace

// A case with a [flow] section is a single-phase air case (flow_case.hpp); any other is a
// particle case, with or without air.
int run_case_file(const RunRequest& r) {
  Config cfg = load(r);
  if (is_flow_case(cfg)) {
    if (!r.restart.empty()) throw Error("--restart: flow cases ([flow]) have no checkpoints; run them afresh");
    if (r.distributed)
      throw ConfigError("flow cases ([flow]) run on one process: start them without an MPI launcher");
    FlowCase f = read_flow_case(cfg);
    cfg.check_unused();
    if (r.check) {
      fmt::print("{}: valid: flow case {} on {} x {} cells, {} steps to {:g} s (checked, not run)\n", r.case_file, f.kind,
                 f.n, f.n, f.steps, f.t_end);
      return 0;
    }
    make_output_folder(cfg, f.output_dir);
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
  if (r.check) {
    // The scene and the insertion as the run would make them (the air's fields are not
    // allocated: read_air_case bounded the grid).
    auto dem = build_solver(c, case_folder(r.case_file));
    long planned = 0;
    for (const auto& ins : c.inserts) planned += ins.count;
    fmt::print("{}: valid: {} parcels ({} inserted in {} region(s), {} from files), {} species, {} wall parts, {}, "
               "t = {:g} .. {:g} s in steps of {:g} s (checked, not run)\n",
               r.case_file, dem->particles().size(), planned, c.inserts.size(),
               static_cast<long>(dem->particles().size()) - planned, c.species.size(), dem->scene().parts().size(),
               air.enabled ? fmt::format("air on {} x {} x {} cells", air.grid.nx, air.grid.ny, air.grid.nz)
                           : std::string("vacuum"),
               c.t_start, c.t_end, c.dem.dt);
    return 0;
  }
  make_output_folder(cfg, c.output.dir);
  remove_stale_temporaries(c.output.dir);
  const RunInfo info{r.case_file, cfg.resolved_toml(), r.restart};
  if (r.distributed) {
#ifdef CGDEM_WITH_MPI
    run::MpiDomain ranks(MPI_COMM_WORLD);
    return run_particle_case(ranks, c, air, diag, info);
#else
    throw Error("this build of cgdem has no MPI (configured with CGDEM_MPI=OFF or without OpenMPI)");
#endif
  }
  run::SerialDomain one_process;
  return run_particle_case(one_process, c, air, diag, info);
}

// The configuration run_case_file would write to config.resolved.toml (validated, nothing
// run). Used by `cgdem converge --reuse`.
std::string resolve_case_file(const RunRequest& r) {
  Config cfg = load(r);
  read_case(cfg);
  cfg.check_unused();
  return cfg.resolved_toml();
}

}  // namespace cgdem::app
