// Pressure-solve benchmark on the die-filling grid (default 140 x 70 x 50, dx = 0.6 mm,
// domain 84 x 42 x 30 mm).
//
// The problem: die_fill_problem.hpp (the die-filling pattern of packed powder, air and walls).
// Prints per method the set-up time, seconds per solve to ||r|| <= 1e-8 ||b|| from phi = 0,
// iterations and true residual (solve-s: mean over the repeats, best-s: the fastest one, as the
// machine may be shared); last line "pressure-solve-s: <fastest preconditioned, mean>".
// Methods: pcg-fft, pcg-fft-plain, pcg-mg, pcg-mg2, pcg-mgw3 (mixed precision), pcg-mg-f64,
// pcg-mg2-f64, pcg-mgw3-f64 (double cycle), cg, cholmod; the environment variable CGDEM_BENCH_METHODS (comma-separated
// list) restricts the set. best-cpu-s: the least processor time (all threads) of one solve.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/pressure/die_fill_problem.hpp"
#include "core/timers.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::bench {

namespace {
using namespace cgdem::pressure;

// Processor time of the process (all threads): on a shared machine, with one thread, close to
// the wall time the solve would take on a quiet one.
double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

struct Row {
  double setup = 0, per_solve = 0, best = 0, rel_res = 0, cpu_best = 0;
  int iters = 0;
  bool ok = false;
};

Row run_method(const DieFillProblem& f, const std::string& method, int repeats) {
  SolverOptions opt;
  opt.method = method;
  opt.rel_tol = 1e-8;
  opt.max_iter = method == "cg" ? 5000 : 1000;
  Row row;
  Stopwatch sw;
  auto solver = make_pressure_solver(f.g, opt);
  solver->set_coefficients(f.ax, f.ay, f.az);
  row.setup = sw.seconds();
  std::vector<double> phi(f.g.cells());
  double total = 0;
  row.best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {
    std::fill(phi.begin(), phi.end(), 0.0);
    const double cpu0 = process_cpu_seconds();
    const auto st = solver->solve(f.rhs, phi);
    row.cpu_best = r == 0 ? process_cpu_seconds() - cpu0 : std::min(row.cpu_best, process_cpu_seconds() - cpu0);
    total += st.seconds;
    row.best = std::min(row.best, st.seconds);
    row.iters = st.iterations;
    row.rel_res = st.rel_residual;
    row.ok = st.converged;
  }
  row.per_solve = total / repeats;
  return row;
}
}  // namespace

int run_pressure_bench(const PressureBenchArgs& args) {
  omp_set_num_threads(args.threads);
  const DieFillProblem f = die_fill_problem(args.nx, args.ny, args.nz);
  std::printf("pressure bench: grid %dx%dx%d (%ld cells), dx = %.3g mm, %d threads, %d repeats\n", args.nx,
              args.ny, args.nz, f.g.cells(), f.g.dx * 1e3, args.threads, args.repeats);
  std::printf("%-14s %10s %12s %12s %8s %12s %5s %10s\n", "method", "setup-s", "solve-s", "best-s", "iters", "rel-resid",
              "conv", "best-cpu-s");
  double best = std::numeric_limits<double>::infinity();
  std::vector<std::string> methods = {"pcg-fft",    "pcg-fft-plain", "pcg-mg",       "pcg-mg2", "pcg-mgw3",
                                      "pcg-mg-f64", "pcg-mg2-f64",   "pcg-mgw3-f64", "cg"};
  if (const char* only = std::getenv("CGDEM_BENCH_METHODS")) {  // e.g. "pcg-mg2,pcg-mg2-f64"
    methods.clear();
    std::string list = only;
    for (size_t a = 0; a <= list.size();) {
      const size_t b = std::min(list.find(',', a), list.size());
      if (b > a) methods.push_back(list.substr(a, b - a));
      a = b + 1;
    }
  }
  if (args.with_cholmod) methods.push_back("cholmod");
  for (const auto& m : methods) {
    Row r;
    try {
      r = run_method(f, m, m == "cg" || m == "cholmod" ? 1 : args.repeats);
    } catch (const std::exception& e) {
      std::printf("%-14s skipped: %s\n", m.c_str(), e.what());
      continue;
    }
    std::printf("%-14s %10.4f %12.4f %12.4f %8d %12.2e %5s %10.4f\n", m.c_str(), r.setup, r.per_solve, r.best, r.iters,
                r.rel_res, r.ok ? "yes" : "NO", r.cpu_best);
    if (r.ok && m.rfind("pcg-", 0) == 0) best = std::min(best, r.per_solve);
  }
  std::printf("pressure-solve-s: %.4f\n", best);
  return 0;
}

}  // namespace cgdem::bench
