// Benchmark of the distributed pressure solve (issue 6, item 3): run as
//     mpirun -np <ranks> bench_pressure_mpi [--grid NX NY NZ] [--repeats R] [--prec a,b,...]
// on the die-filling grid (default 140 x 70 x 50 cells of 0.6 mm, 84 x 42 x 30 mm), cut by
// GridBlocks (choose_dims: 2 ranks give 2 x 1 x 1). The problem is that of `cgdem bench
// pressure` (bench/pressure/die_fill_problem.hpp): a = dt/rho in free air, about 1e-3 of that
// in the packed die and shoe cavity, 0 on faces touching the solid table and shoe walls; Open
// top, Wall elsewhere; rhs deterministic noise in the air cells. Every solve starts from
// phi = 0 with rel_tol 1e-8.
//
// Prints, per preconditioner: set-up seconds, iterations, true relative residual, seconds per
// solve (mean over the repeats and the best; each the slowest rank's time), and the largest
// difference from the serial pcg-mg solution. On one rank it also prints the serial solvers
// ("serial pcg-mg", "serial pcg-fft") for comparison.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "solvers/pressure_mpi/dist_pressure.hpp"
#include "solvers/pressure_mpi/pfmg.hpp"
#include "bench/pressure/die_fill_problem.hpp"
#include "core/error.hpp"

namespace {

using namespace cgdem;

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
  const bench::DieFillProblem p = bench::die_fill_problem(nx, ny, nz);
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
    s->set_coefficients(p.ax, p.ay, p.az);
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
      s->set_coefficients(p.ax, p.ay, p.az);
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
    solver.set_coefficients(air_mpi::block_part(blocks, p.ax, 0), air_mpi::block_part(blocks, p.ay, 1),
                            air_mpi::block_part(blocks, p.az, 2));
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
