// Benchmark of the distributed pressure solve (issue 6, item 3): run as
//     mpirun -np <ranks> bench_pressure_mpi [--grid NX NY NZ] [--repeats R] [--prec a,b,...]
// on the die-filling grid (default 140 x 70 x 50 cells of 0.6 mm, 84 x 42 x 30 mm), cut by
// GridBlocks (choose_dims: 2 ranks give 2 x 1 x 1). The coefficients follow the pattern of
// `cgdem bench pressure` (bench/pressure/pressure_bench.cpp): a = dt/rho in free air,
// eps^2 / (eps rho/dt + beta) with Ergun's beta in the packed die and shoe cavity (eps = 0.45,
// about 1e-3 of the air value), a = 0 on faces touching the solid table and shoe walls, face
// values the harmonic mean of the two cells; Open top, Wall elsewhere; rhs deterministic noise
// in the air cells. Every solve starts from phi = 0 with rel_tol 1e-8.
//
// Prints, per preconditioner: set-up seconds, iterations, true relative residual, seconds per
// solve (mean over the repeats and the best; each the slowest rank's time), and the largest
// difference from the serial pcg-mg solution. On one rank it also prints the serial solvers
// ("serial pcg-mg", "serial pcg-fft") for comparison.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "air_mpi/dist_pressure.hpp"
#include "air_mpi/pfmg.hpp"
#include "core/error.hpp"

namespace {

using namespace cgdem;
using pressure::Boundary;

struct Problem {
  pressure::GridSpec g;
  std::vector<double> a[3], rhs;
};

Problem die_fill(int nx, int ny, int nz) {
  Problem p;
  p.g.nx = nx, p.g.ny = ny, p.g.nz = nz;
  p.g.dx = 84e-3 / nx, p.g.dy = 42e-3 / ny, p.g.dz = 30e-3 / nz;
  p.g.bc = {Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Open};
  // Semi-implicit drag: a = eps^2 / (eps rho/dt + beta), beta from Ergun (d = 125 um, slip 5 cm/s).
  const double mu = 1.8e-5, rho = 1.0, dt = 1e-4, d = 125e-6, slip = 0.05, eps = 0.45;
  const double beta = 150 * mu * (1 - eps) * (1 - eps) / (eps * d * d) + 1.75 * (1 - eps) * rho * slip / d;
  const double a_bed = eps * eps / (eps * rho / dt + beta), a_air = dt / rho;
  auto box = [](double x, double y, double z, double x0, double x1, double y0, double y1, double z0, double z1) {
    return x >= x0 && x <= x1 && y >= y0 && y <= y1 && z >= z0 && z <= z1;
  };
  std::vector<double> cell(p.g.cells());
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = (i + 0.5) * p.g.dx * 1e3, y = (j + 0.5) * p.g.dy * 1e3, z = (k + 0.5) * p.g.dz * 1e3;
        const bool die = box(x, y, z, 37, 47, 6, 36, 2, 14), cavity = box(x, y, z, 22, 32, 6, 36, 14, 24);
        const bool solid = (z < 14 && !die) || (box(x, y, z, 19, 35, 3, 39, 14, 24) && !cavity);
        cell[i + long(nx) * (j + long(ny) * k)] = solid ? 0.0 : (die || cavity) ? a_bed : a_air;
      }
  const int n[3] = {nx, ny, nz};
  for (int ax = 0; ax < 3; ++ax) {
    int e[3] = {nx, ny, nz};
    e[ax] += 1;
    p.a[ax].resize(long(e[0]) * e[1] * e[2]);
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          int lo[3] = {i, j, k}, hi[3] = {i, j, k};
          lo[ax] = std::max(lo[ax] - 1, 0);   // a boundary face takes its one cell twice
          hi[ax] = std::min(hi[ax], n[ax] - 1);
          const double u = cell[lo[0] + long(nx) * (lo[1] + long(ny) * lo[2])];
          const double v = cell[hi[0] + long(nx) * (hi[1] + long(ny) * hi[2])];
          p.a[ax][i + long(e[0]) * (j + long(e[1]) * k)] = (u > 0 && v > 0) ? 2 * u * v / (u + v) : 0.0;
        }
  }
  p.rhs.resize(p.g.cells());
  std::uint64_t s = 88172645463325252ull;
  for (long c = 0; c < p.g.cells(); ++c) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    p.rhs[c] = cell[c] > 0 ? 2.0 * double(s >> 11) / double(1ull << 53) - 1.0 : 0.0;
  }
  return p;
}


double slowest(double t) {
  MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return t;
}

int run(int argc, char** argv) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int nx = 140, ny = 70, nz = 50, repeats = 3;
  std::string precs = "bj-mg,bj-mg2,bj-fft,pfmg";
  for (int q = 1; q < argc; ++q) {
    const std::string a = argv[q];
    if (a == "--grid" && q + 3 < argc) nx = std::atoi(argv[++q]), ny = std::atoi(argv[++q]), nz = std::atoi(argv[++q]);
    else if (a == "--repeats" && q + 1 < argc) repeats = std::max(1, std::atoi(argv[++q]));
    else if (a == "--prec" && q + 1 < argc) precs = argv[++q];
    else throw Error("bench_pressure_mpi: unknown argument '" + a + "' (--grid NX NY NZ, --repeats R, --prec a,b)");
  }
  const Problem p = die_fill(nx, ny, nz);
  const air_mpi::GridBlocks blocks({nx, ny, nz}, size, rank);
  if (rank == 0)
    std::printf("grid %d x %d x %d (%ld cells), %d ranks as %d x %d x %d blocks, OMP threads %s, %d repeats, "
                "rel_tol 1e-8\n",
                nx, ny, nz, p.g.cells(), size, blocks.dims()[0], blocks.dims()[1], blocks.dims()[2],
                std::getenv("OMP_NUM_THREADS") ? std::getenv("OMP_NUM_THREADS") : "(unset)", repeats);

  // The serial reference solution (every rank solves it; only rank 0's timing is printed).
  std::vector<double> ref(p.g.cells(), 0.0);
  {
    pressure::SolverOptions so;
    so.method = "pcg-mg";
    so.rel_tol = 1e-12;
    auto s = pressure::make_pressure_solver(p.g, so);
    s->set_coefficients(p.a[0], p.a[1], p.a[2]);
    s->solve(p.rhs, ref);
  }
  double ref_max = 0;
  for (double v : ref) ref_max = std::max(ref_max, std::abs(v));
  if (size == 1)
    for (const char* m : {"pcg-mg", "pcg-fft"}) {
      pressure::SolverOptions so;
      so.method = m;
      so.rel_tol = 1e-8;
      auto s = pressure::make_pressure_solver(p.g, so);
      const double t0 = MPI_Wtime();
      s->set_coefficients(p.a[0], p.a[1], p.a[2]);
      const double setup = MPI_Wtime() - t0;
      double sum = 0, best = 1e300;
      pressure::SolveStats st;
      for (int r = 0; r < repeats; ++r) {
        std::vector<double> phi(p.g.cells(), 0.0);
        st = s->solve(p.rhs, phi);
        sum += st.seconds, best = std::min(best, st.seconds);
      }
      std::printf("serial %-8s setup-s %.3f iterations %4d rel-res %.2e solve-s %.3f best-s %.3f\n", m, setup,
                  st.iterations, st.rel_residual, sum / repeats, best);
    }

  std::stringstream list(precs);
  std::string name;
  const std::vector<double> rhs = air_mpi::block_part(blocks, p.rhs, -1);
  const std::vector<double> want = air_mpi::block_part(blocks, ref, -1);
  while (std::getline(list, name, ',')) {
    if (name == "pfmg" && !air_mpi::have_pfmg()) {
      if (rank == 0) std::printf("dist   %-8s (not built: no hypre)\n", name.c_str());
      continue;
    }
    air_mpi::DistOptions opt;
    opt.preconditioner = name;
    opt.rel_tol = 1e-8;
    opt.max_iter = name == "none" ? 5000 : 1000;
    air_mpi::DistPressureSolver solver(MPI_COMM_WORLD, blocks, p.g, opt);
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    solver.set_coefficients(air_mpi::block_part(blocks, p.a[0], 0), air_mpi::block_part(blocks, p.a[1], 1),
                            air_mpi::block_part(blocks, p.a[2], 2));
    const double setup = slowest(MPI_Wtime() - t0);
    double sum = 0, best = 1e300, err = 0;
    pressure::SolveStats st;
    for (int r = 0; r < repeats; ++r) {
      std::vector<double> phi(blocks.local_count(), 0.0);
      MPI_Barrier(MPI_COMM_WORLD);
      st = solver.solve(rhs, phi);
      const double t = slowest(st.seconds);
      sum += t, best = std::min(best, t);
      for (long c = 0; c < blocks.local_count(); ++c) err = std::max(err, std::abs(phi[c] - want[c]));
    }
    err = slowest(err) / ref_max;
    if (rank == 0)
      std::printf("dist   %-8s setup-s %.3f iterations %4d rel-res %.2e solve-s %.3f best-s %.3f "
                  "max|phi-serial|/max|phi| %.1e%s\n",
                  name.c_str(), setup, st.iterations, st.rel_residual, sum / repeats, best, err,
                  st.converged ? "" : " NOT CONVERGED");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int code = 0;
  try {
    code = run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pressure_mpi: %s\n", e.what());
    code = 1;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return code;
}
