// The cgdem command line.
//   cgdem run CASE.toml [--set key.path=value ...] [--output DIR] [--threads N] [--restart CHECKPOINT] [--check]
//   cgdem bench dem --bed BED.csv [--steps N] [--threads T] [--stripped [--accounts]] [--no-accounts] [--box-x LX ...]
//   cgdem bench pressure [--grid NXxNYxNZ] [--threads T] [--no-cholmod]
//   cgdem bench fluid [--grid NXxNYxNZ] [--threads T] [--steps N] [--time-order 1|2] [--method M]
//   cgdem keys [--output FILE] [--check CASE ...]     (the case keys' reference, app/case_keys.hpp)
//   cgdem spectrum | converge | scale | compare ...   (the analysis commands, scaling/*_command.hpp)
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "app/case_keys.hpp"
#include "app/launcher.hpp"
#include "app/run_command.hpp"
#include "bench/bench.hpp"
#include "contact/laws.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "geometry/primitives.hpp"
#include "scaling/compare_command.hpp"
#include "scaling/converge_command.hpp"
#include "scaling/scale_command.hpp"
#include "scaling/spectrum_command.hpp"
#include "solvers/pressure/pressure_solver.hpp"
#ifdef CGDEM_WITH_MPI
#include "app/mpi/run_distributed.hpp"
#endif

// OpenBLAS (behind CHOLMOD, used on the coarsest multigrid level) starts its own pthreads,
// which keep spinning after each call and take the cores from the OpenMP threads of the DEM
// and the air: on 2 cores a coupled step was up to 100x slower with 2 threads than with 1.
// The BLAS work here is small, so it runs on the calling thread. Weak: absent without OpenBLAS.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace {

template <class Args>
int parse_grid(const std::string& g, Args& a) {
  if (std::sscanf(g.c_str(), "%dx%dx%d", &a.nx, &a.ny, &a.nz) != 3 || a.nx < 2 || a.ny < 2 || a.nz < 2)
    throw cgdem::Error("--grid: expected NXxNYxNZ with every size >= 2, got '" + g + "'");
  return 0;
}

// The values of `cgdem run` and its subcommand (parsed is *sub).
struct RunArgs {
  std::string case_file, output, restart;
  std::vector<std::string> sets;
  bool check_only = false;
  CLI::App* sub = nullptr;
};

// Adds `run` to app; its --threads writes the same `threads` as the global option. The
// values land in a, which must outlive the parsing.
void add_run_command(CLI::App& app, RunArgs& a, int& threads) {
  auto* run = a.sub = app.add_subcommand("run", "run a case");
  run->add_option("case", a.case_file, "case file (TOML)")->required()->check(CLI::ExistingFile);
  run->add_option("--set", a.sets, "override a key: key.path=value (repeatable)");
  run->add_option("--output", a.output, "output folder (overrides output.dir)");
  run->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  run->add_option("--restart", a.restart, "continue from a checkpoint (OUTPUT/checkpoint.bin of the same case)")
      ->check(CLI::ExistingFile);
  run->add_flag("--check", a.check_only,
                "validate the whole configuration, build the scene and insert the parcels, then exit without "
                "stepping or writing (exit 0: valid)");
  run->footer(fmt::format("Contact laws ([contact] law, the first is the default):\n{}\nWall primitives "
                          "([[walls.body.part]] type):\n{}",
                          cgdem::contact::contact_law_help(), cgdem::geometry::wall_primitive_help()));
}

// The values of `cgdem bench dem | pressure | fluid` and their subcommands.
struct BenchArgs {
  cgdem::bench::DemBenchArgs dem;
  cgdem::bench::PressureBenchArgs pressure;
  std::string pressure_grid = "140x70x50";
  bool no_cholmod = false;
  cgdem::bench::FluidBenchArgs fluid;
  std::string fluid_grid = "140x70x50";
  CLI::App *dem_sub = nullptr, *pressure_sub = nullptr, *fluid_sub = nullptr;
};

// Adds `bench` and its three subcommands to app; the values land in a.
void add_bench_commands(CLI::App& app, BenchArgs& a) {
  auto* bench = app.add_subcommand("bench", "performance benchmarks (print figures)");
  bench->require_subcommand(1);
  auto* bdem = a.dem_sub =
      bench->add_subcommand("dem", "dense-bed DEM benchmark (a settled bed of spheres, CSV x,y,z,d in m)");
  bdem->add_option("--bed", a.dem.bed, "bed CSV (x,y,z,d)")->required()->check(CLI::ExistingFile);
  bdem->add_option("--steps", a.dem.steps, "time steps")->check(CLI::PositiveNumber);
  bdem->add_option("--threads", a.dem.threads, "OpenMP threads")->check(CLI::PositiveNumber);
  bdem->add_flag("--stripped", a.dem.stripped,
                 "run the stripped reference of the same law instead of the engine (one thread; a bound)");
  bdem->add_flag("--accounts", a.dem.accounts, "with --stripped: keep the energy accounts as the engine does")
      ->needs(bdem->get_option("--stripped"));
  bdem->add_flag("--no-accounts", a.dem.no_accounts,
                 "the engine without its energy accounts (as output.energy_accounts = false: the same motion)")
      ->excludes(bdem->get_option("--stripped"));
  bdem->add_option("--box-x", a.dem.box_x, "box length along x [m] (walls at 0 and there; default 0.010)")
      ->check(CLI::PositiveNumber);
  bdem->add_option("--box-y", a.dem.box_y, "box length along y [m] (walls at 0 and there; default 0.006)")
      ->check(CLI::PositiveNumber);
  bdem->add_option("--rebuild-every", a.dem.rebuild_every,
                   "rebuild the neighbour lists every N steps whether or not the particles moved (default 0: when "
                   "the rebuild test asks)")
      ->check(CLI::NonNegativeNumber)
      ->excludes(bdem->get_option("--stripped"));
  bdem->add_option("--law", a.dem.law,
                   fmt::format("contact law, with its default material: {} (default linear: the paper's Table 1)",
                               fmt::join(cgdem::contact::contact_law_names(), ", ")))
      ->check(CLI::IsMember(cgdem::contact::contact_law_names()));
  auto* bpress = a.pressure_sub = bench->add_subcommand("pressure", "pressure solve on the die-filling grid");
  bpress->add_option("--grid", a.pressure_grid, "NXxNYxNZ");
  bpress->add_option("--threads", a.pressure.threads, "OpenMP threads")->check(CLI::PositiveNumber);
  bpress->add_option("--repeats", a.pressure.repeats, "solves to average")->check(CLI::PositiveNumber);
  bpress->add_flag("--no-cholmod", a.no_cholmod, "skip the (slow) direct CHOLMOD reference");
  auto* bfluid = a.fluid_sub =
      bench->add_subcommand("fluid", "one full air step on the die-filling grid (per-phase table)");
  bfluid->add_option("--grid", a.fluid_grid, "NXxNYxNZ (cubic cells on the 84 x 42 x 30 mm domain)");
  bfluid->add_option("--threads", a.fluid.threads, "OpenMP threads")->check(CLI::PositiveNumber);
  bfluid->add_option("--steps", a.fluid.steps, "timed steps")->check(CLI::PositiveNumber);
  bfluid->add_option("--warmup", a.fluid.warmup, "untimed steps first")->check(CLI::NonNegativeNumber);
  bfluid->add_option("--time-order", a.fluid.time_order, "1: Euler, 2: Heun")->check(CLI::Range(1, 2));
  bfluid->add_option("--method", a.fluid.method,
                     fmt::format("pressure solver: {}", fmt::join(cgdem::pressure::pressure_method_names(), ", ")));
  bfluid->add_option("--tolerance", a.fluid.tolerance, "relative residual of the pressure solves")
      ->check(CLI::PositiveNumber);
  bfluid->add_option("--stage-tolerance", a.fluid.stage_tolerance, "relative residual of the Heun stage-1 solve");
}

// The selected benchmark after parsing (its exit code), or nothing when none is.
std::optional<int> run_bench(BenchArgs& a) {
  if (*a.dem_sub) return cgdem::bench::run_dem_bench(a.dem);
  if (*a.pressure_sub) {
    parse_grid(a.pressure_grid, a.pressure);
    a.pressure.with_cholmod = !a.no_cholmod;
    return cgdem::bench::run_pressure_bench(a.pressure);
  }
  if (*a.fluid_sub) {
    parse_grid(a.fluid_grid, a.fluid);
    return cgdem::bench::run_fluid_bench(a.fluid);
  }
  return std::nullopt;
}

// The values of `cgdem keys` and its subcommand.
struct KeysArgs {
  std::string output;
  std::vector<std::string> check;
  CLI::App* sub = nullptr;
};

void add_keys_command(CLI::App& app, KeysArgs& a) {
  a.sub = app.add_subcommand("keys", "the reference of every case key: name, type, unit, default, allowed "
                                     "values, meaning (Markdown, as docs/case_keys.md)");
  a.sub->add_option("--output", a.output, "write it to this file instead of printing it");
  a.sub->add_option("--check", a.check, "case files: list their keys that the reference lacks (exit 1 if any)")
      ->check(CLI::ExistingFile);
}

// The analysis commands (scaling/*_command.hpp), added to the app in the order of --help.
struct AnalysisCommands {
  explicit AnalysisCommands(CLI::App& app) : spectrum(app), converge(app), scale(app), compare(app) {}
  // The selected one's exit code after parsing, or nothing when none is selected.
  std::optional<int> run_selected() const {
    if (spectrum.selected()) return spectrum.run();
    if (converge.selected()) return converge.run();
    if (scale.selected()) return scale.run();
    if (compare.selected()) return compare.run();
    return std::nullopt;
  }
  cgdem::scaling::SpectrumCommand spectrum;
  cgdem::scaling::ConvergeCommand converge;
  cgdem::scaling::ScaleCommand scale;
  cgdem::scaling::CompareCommand compare;
};

// `cgdem run` in this process (OpenMP threads as given).
int run_case(const RunArgs& run, int threads) {
  if (threads > 0) omp_set_num_threads(threads);
  cgdem::app::RunRequest request{run.case_file, run.sets, run.output, run.restart};
  request.check = run.check_only;
  return cgdem::app::run_case_file(request);
}

// Ends the process after an error was printed, without the exit handlers: after a failed
// write (disk full, file-size limit) HDF5 1.10's own exit handler tries again to flush the
// file it could not close and crashes (SIGSEGV in H5F__close_cb), which would turn the
// reported error into a signal. The standard streams (and any open CSV) are flushed first.
[[noreturn]] void stop_after_error(int status) {
  std::fflush(nullptr);
  std::_Exit(status);
}

}  // namespace

// The command line: the commands are added in the order of `cgdem --help` (run, bench,
// keys, the analysis commands), parsed, and the selected one runs in this process (or, for
// `run` under a launcher with N > 1 processes, over MPI ranks). A cgdem::Error or a
// library's exception stops the process with a message (exit 2 or 3).
int main(int argc, char** argv) {
  CLI::App app{"cgdem: coarse-grained DEM-CFD for powder die filling"};
  app.set_version_flag("--version", fmt::format("cgdem {} (revision {})", cgdem::kVersion, cgdem::kGitRevision));
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  RunArgs run;
  add_run_command(app, run, threads);
  BenchArgs bench;
  add_bench_commands(app, bench);
  KeysArgs keys;
  add_keys_command(app, keys);
  AnalysisCommands analysis(app);  // CLI11 writes the parsed options into its members

  CLI11_PARSE(app, argc, argv);
  // A file-size limit (ulimit -f) must make write() fail with EFBIG, which the writers
  // report with the file's name, instead of killing the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  if (openblas_set_num_threads) openblas_set_num_threads(1);
  const auto launched = cgdem::app::launched_as();
#ifdef CGDEM_WITH_MPI
  // `cgdem run` over MPI ranks: under a launcher with N > 1 processes (a checkpoint restarts
  // on any number of ranks, one process included, without the launcher).
  if (*run.sub && launched.size > 1) {
    if (threads > 0) omp_set_num_threads(threads);
    return cgdem::app::run_distributed_main(argc, argv, {run.case_file, run.sets, run.output, run.restart});
  }
#endif
  try {
    // Under `mpirun -np N` (N > 1) every other command stops before doing anything; only
    // the first process says why, so the message is not repeated N times.
    try {
      cgdem::app::require_single_process(launched, app.get_subcommands().front()->get_name());
    } catch (const cgdem::Error&) {
      if (launched.rank != 0) return 2;
      throw;
    }
    if (*run.sub) return run_case(run, threads);
    if (*keys.sub) return cgdem::app::keys_command(keys.output, keys.check);
    if (const auto status = run_bench(bench)) return *status;
    if (const auto status = analysis.run_selected()) return *status;
  } catch (const cgdem::Error& e) {
    std::fprintf(stderr, "cgdem: error: %s\n", e.what());
    stop_after_error(2);
  } catch (const std::exception& e) {  // a library's exception (file system, allocation): still a clean stop
    std::fprintf(stderr, "cgdem: error: %s\n", e.what());
    stop_after_error(3);
  }
  return 0;
}
