// Distributed pressure solve over MPI (issue 6, item 3): the solution on the blocks matches
// the serial make_pressure_solver solution of the same problem, for every preconditioner, on
// the cuts of mpi_air_util.hpp. Problems (all with IBM-like coefficients: faces touching the
// solid carry a = 0, others vary smoothly around 1):
//   * "solid, open top":  a solid box on the floor, Wall sides, Open top;
//   * "pocket":           plus an air pocket sealed by zero faces, cut by the blocks: a
//                         floating component spread over several ranks;
//   * "all walls":        singular: the solution is mean-free (checked) and equals the serial one.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../../error_of.hpp"
#include "solvers/pressure_mpi/dist_pressure.hpp"
#include "solvers/pressure_mpi/pfmg.hpp"
#include "mpi_air_util.hpp"

namespace cgdem::air_mpi {
namespace {

using pressure::Boundary;
using test::maxed;
using test::world_rank;

const std::array<int, 3> kCells{24, 14, 10};

struct Problem {
  const char* name;
  pressure::GridSpec grid;
  std::vector<double> a[3];  // global MAC layout of pressure_solver.hpp
  std::vector<double> rhs;   // global cells
};

bool in_solid(int i, int j, int k) { return i >= 8 && i < 14 && j >= 4 && j < 10 && k < 6; }

Problem make_problem(const char* name, bool open_top, bool pocket) {
  Problem p;
  p.name = name;
  p.grid.nx = kCells[0], p.grid.ny = kCells[1], p.grid.nz = kCells[2];
  p.grid.dx = p.grid.dy = p.grid.dz = 6e-4;
  if (open_top) p.grid.bc[5] = Boundary::Open;
  const int n[3] = {kCells[0], kCells[1], kCells[2]};
  for (int d = 0; d < 3; ++d) {
    int e[3] = {n[0], n[1], n[2]};
    e[d] += 1;
    p.a[d].resize(long(e[0]) * e[1] * e[2]);
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          int lo[3] = {i, j, k}, hi[3] = {i, j, k};
          lo[d] -= 1;  // the face of index m along d sits between cells m-1 and m
          auto solid = [&](int* c) {
            return c[0] >= 0 && c[0] < n[0] && c[1] >= 0 && c[1] < n[1] && c[2] >= 0 && c[2] < n[2] &&
                   in_solid(c[0], c[1], c[2]);
          };
          double a = 1.0 + 0.5 * std::sin(0.3 * i + 0.2 * j + 0.1 * k + d);
          if (solid(lo) || solid(hi)) a = 0;
          // The pocket [2, 20) x [11, 14) x [0, 4): sealed by zero faces at x = 2, 20, y = 11, z = 4.
          if (pocket) {
            const bool in_x = i >= 2 && i < 20, in_y = j >= 11, in_z = k < 4;
            if ((d == 0 && (i == 2 || i == 20) && in_y && in_z) || (d == 1 && j == 11 && in_x && in_z) ||
                (d == 2 && k == 4 && in_x && in_y))
              a = 0;
          }
          p.a[d][i + long(e[0]) * (j + long(e[1]) * k)] = a;
        }
  }
  p.rhs.resize(p.grid.cells());
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        p.rhs[i + long(n[0]) * (j + long(n[1]) * k)] = 1e4 * std::cos(0.4 * i - 0.3 * j + 0.2 * k) + 2e3;
  return p;
}


std::vector<std::string> preconditioners() {
  std::vector<std::string> p{"none", "bj-mg", "bj-fft", "as-mg", "as-mg2"};
  if (have_pfmg()) p.push_back("pfmg");
  return p;
}

void check_against_serial(const Problem& prob) {
  pressure::SolverOptions so;
  so.method = "pcg-mg";
  so.rel_tol = 1e-13;
  auto serial = pressure::make_pressure_solver(prob.grid, so);
  serial->set_coefficients(prob.a[0], prob.a[1], prob.a[2]);
  std::vector<double> ref(prob.grid.cells(), 0.0);
  const auto sst = serial->solve(prob.rhs, ref);
  ASSERT_TRUE(sst.converged);
  double ref_max = 0;
  for (double v : ref) ref_max = std::max(ref_max, std::abs(v));
  ASSERT_GT(ref_max, 0);
  for (const GridBlocks& b : test::layouts(kCells)) {
    const std::string layout = fmt::format("{}x{}x{}", b.dims()[0], b.dims()[1], b.dims()[2]);
    const std::vector<double> want = block_part(b, ref, -1), rhs = block_part(b, prob.rhs, -1);
    for (const std::string& pc : preconditioners()) {
      DistOptions opt;
      opt.preconditioner = pc;
      opt.rel_tol = 1e-10;
      opt.max_iter = 2000;
      DistPressureSolver solver(MPI_COMM_WORLD, b, prob.grid, opt);
      solver.set_coefficients(block_part(b, prob.a[0], 0), block_part(b, prob.a[1], 1), block_part(b, prob.a[2], 2));
      std::vector<double> phi(b.local_count(), 0.0);
      const auto st = solver.solve(rhs, phi);
      double err = 0, sum = 0;
      for (long c = 0; c < b.local_count(); ++c) err = std::max(err, std::abs(phi[c] - want[c])), sum += phi[c];
      err = maxed(err) / ref_max;
      MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      if (world_rank() == 0)
        std::printf("[ pressure ] %-15s %s %-6s: %4d iterations (serial pcg-mg %d), rel. residual %.2e, "
                    "max |phi - serial| / max |phi| = %.2e, %d floating components\n",
                    prob.name, layout.c_str(), pc.c_str(), st.iterations, sst.iterations, st.rel_residual, err,
                    solver.op().floating_components());
      EXPECT_TRUE(st.converged) << prob.name << " " << layout << " " << pc;
      EXPECT_LT(err, 1e-6) << prob.name << " " << layout << " " << pc;
      if (prob.grid.bc[5] != Boundary::Open) {
        EXPECT_LT(std::abs(sum) / (ref_max * prob.grid.cells()), 1e-12) << "not mean-free";
      }
    }
  }
}

TEST(AirPressure, SolidOpenTopMatchesSerial) { check_against_serial(make_problem("solid, open top", true, false)); }
TEST(AirPressure, FloatingPocketAcrossRanksMatchesSerial) { check_against_serial(make_problem("pocket", true, true)); }
TEST(AirPressure, AllWallsIsMeanFreeAndMatchesSerial) { check_against_serial(make_problem("all walls", false, false)); }

TEST(AirPressure, BadInputIsRefused) {
  const GridBlocks b = test::layouts(kCells).front();
  pressure::GridSpec g;
  g.nx = kCells[0], g.ny = kCells[1], g.nz = kCells[2];
  pressure::GridSpec per = g;
  per.bc[0] = per.bc[1] = Boundary::Periodic;
  EXPECT_NE(cgdem::test::error_of([&] { DistPressureSolver(MPI_COMM_WORLD, b, per, {}); }).find("periodic"),
            std::string::npos);
  DistOptions bad;
  bad.preconditioner = "ilu";
  EXPECT_NE(cgdem::test::error_of([&] { DistPressureSolver(MPI_COMM_WORLD, b, g, bad); }).find("unknown"),
            std::string::npos);
  DistPressureSolver s(MPI_COMM_WORLD, b, g, {});
  std::vector<double> few(3, 1.0);
  EXPECT_NE(cgdem::test::error_of([&] { s.set_coefficients(few, few, few); }).find("entries"), std::string::npos);
}

}  // namespace
}  // namespace cgdem::air_mpi
