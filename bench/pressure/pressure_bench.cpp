// Pressure-solve benchmark on the die-filling grid (default 140 x 70 x 50, dx = 0.6 mm,
// domain 84 x 42 x 30 mm).
//
// Face coefficient of the pressure equation from the semi-implicit momentum update
//   eps rho_f (u* - u^n)/dt = -eps grad p - beta (u* - v)
//   =>  u* = (eps rho_f/dt u^n + beta v - eps grad p) / (eps rho_f/dt + beta),
// so div(eps u*) = 0 gives div(a grad p) = rhs with a = eps^2 / (eps rho_f/dt + beta).
// beta from Ergun (physics.md, eq. (9) of the paper, Ergun branch):
//   beta = 150 mu (1-eps)^2 / (eps d^2) + 1.75 (1-eps) rho_f |u-v| / d,
// d = 125 um, mu = 1.8e-5 Pa s, rho_f = 1 kg/m^3, dt = 1e-4 s, |u-v| = 0.05 m/s.
// Packed (eps = 0.45): the die x in [37,47], y in [6,36], z in [2,14] mm and the shoe cavity
// x in [22,32], y in [6,36], z in [14,24] mm; free air elsewhere (eps = 1, beta = 0).
// Solids (a = 0 on every face touching them): the table z < 14 mm outside the die, and the shoe
// walls, 3 mm thick around the cavity. Domain: Open at +z, Wall elsewhere. Face a = harmonic
// mean of the two cells. rhs: deterministic noise in [-1,1] (all wavelengths) in air cells.
// Prints per method the set-up time, seconds per solve to ||r|| <= 1e-8 ||b|| from phi = 0,
// iterations and true residual (solve-s: mean over the repeats, best-s: the fastest one, as the
// machine may be shared); last line "pressure-solve-s: <fastest preconditioned, mean>".
// Methods: pcg-fft, pcg-fft-plain, pcg-mg, pcg-mg2 (mixed precision), pcg-mg-f64, pcg-mg2-f64
// (double V-cycle), cg, cholmod; the environment variable CGDEM_BENCH_METHODS (comma-separated
// list) restricts the set. best-cpu-s: the least processor time (all threads) of one solve.
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "core/timers.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::bench {

namespace {
using namespace cgdem::pressure;

struct Field {
  GridSpec g;
  std::vector<double> ax, ay, az, rhs;
};

bool in_box(double x, double y, double z, double x0, double x1, double y0, double y1, double z0, double z1) {
  return x >= x0 && x <= x1 && y >= y0 && y <= y1 && z >= z0 && z <= z1;
}

Field die_fill_field(int nx, int ny, int nz) {
  Field f;
  f.g.nx = nx; f.g.ny = ny; f.g.nz = nz;
  f.g.dx = 84e-3 / nx; f.g.dy = 42e-3 / ny; f.g.dz = 30e-3 / nz;
  f.g.bc = {Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Open};
  const double mu = 1.8e-5, rho = 1.0, dt = 1e-4, d = 125e-6, slip = 0.05, eps_bed = 0.45;
  const double beta_bed = 150 * mu * (1 - eps_bed) * (1 - eps_bed) / (eps_bed * d * d) +
                          1.75 * (1 - eps_bed) * rho * slip / d;
  const double a_bed = eps_bed * eps_bed / (eps_bed * rho / dt + beta_bed), a_air = dt / rho;
  std::vector<double> a(f.g.cells());
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = (i + 0.5) * f.g.dx * 1e3, y = (j + 0.5) * f.g.dy * 1e3, z = (k + 0.5) * f.g.dz * 1e3;
        const bool die = in_box(x, y, z, 37, 47, 6, 36, 2, 14), cavity = in_box(x, y, z, 22, 32, 6, 36, 14, 24);
        const bool table = z < 14 && !die;
        const bool shoe = in_box(x, y, z, 19, 35, 3, 39, 14, 24) && !cavity;
        a[i + long(nx) * (j + long(ny) * k)] = (table || shoe) ? 0.0 : (die || cavity) ? a_bed : a_air;
      }
  auto hm = [](double p, double q) { return (p > 0 && q > 0) ? 2 * p * q / (p + q) : 0.0; };
  auto cell = [&](int i, int j, int k) { return a[i + long(nx) * (j + long(ny) * k)]; };
  f.ax.resize(long(nx + 1) * ny * nz);
  f.ay.resize(long(nx) * (ny + 1) * nz);
  f.az.resize(long(nx) * ny * (nz + 1));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i)
        f.ax[i + long(nx + 1) * (j + long(ny) * k)] =
            hm(cell(i > 0 ? i - 1 : i, j, k), cell(i < nx ? i : nx - 1, j, k));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i)
        f.ay[i + long(nx) * (j + long(ny + 1) * k)] =
            hm(cell(i, j > 0 ? j - 1 : j, k), cell(i, j < ny ? j : ny - 1, k));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        f.az[i + long(nx) * (j + long(ny) * k)] =
            hm(cell(i, j, k > 0 ? k - 1 : k), cell(i, j, k < nz ? k : nz - 1));
  f.rhs.resize(f.g.cells());
  std::uint64_t s = 88172645463325252ull;  // xorshift64: deterministic noise
  for (long c = 0; c < f.g.cells(); ++c) {
    s ^= s << 13; s ^= s >> 7; s ^= s << 17;
    f.rhs[c] = a[c] > 0 ? 2.0 * double(s >> 11) / double(1ull << 53) - 1.0 : 0.0;
  }
  return f;
}

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

Row run_method(const Field& f, const std::string& method, int repeats) {
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
  const Field f = die_fill_field(args.nx, args.ny, args.nz);
  std::printf("pressure bench: grid %dx%dx%d (%ld cells), dx = %.3g mm, %d threads, %d repeats\n", args.nx,
              args.ny, args.nz, f.g.cells(), f.g.dx * 1e3, args.threads, args.repeats);
  std::printf("%-14s %10s %12s %12s %8s %12s %5s %10s\n", "method", "setup-s", "solve-s", "best-s", "iters", "rel-resid",
              "conv", "best-cpu-s");
  double best = std::numeric_limits<double>::infinity();
  std::vector<std::string> methods = {"pcg-fft", "pcg-fft-plain", "pcg-mg", "pcg-mg2", "pcg-mg-f64", "pcg-mg2-f64", "cg"};
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
