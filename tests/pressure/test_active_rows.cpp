// The finest grid's loops visit only the cells with D > 0 (active_rows.hpp). Checked here:
// the segments and the work shares themselves, and that skipping the blocked cells changes no
// value anywhere else: Poisson7's A x against the row formula written out cell by cell, and the
// float smoother, restriction and prolongation of stencil32.hpp with and without skipping, on a
// grid shaped like the die-filling one (a table with a hole, a walled shoe with a cavity, single
// blocked cells). The comparisons are exact (==, so +0 and -0 count as equal: a skipped term
// is a zero weight times a value).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "mms.hpp"
#include "solvers/pressure/multigrid.hpp"
#include "solvers/pressure/sundials_pcg.hpp"

using namespace cgdem::pressure;
using B = Boundary;

namespace {

// Blocks every face of the solid cells: a table (k < nz/3) with a hole, a shoe (walls around a
// cavity) above it, and every 97th cell.
void add_solids(test::Problem& p) {
  const int nx = p.g.nx, ny = p.g.ny, nz = p.g.nz;
  auto solid = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return false;
    const long c = i + long(nx) * (j + long(ny) * k);
    if (c % 97 == 0) return true;
    if (k < nz / 3) return !(i >= nx / 3 && i < nx / 3 + 5 && j >= 3 && j < ny - 3);
    const bool in_shoe = i >= nx / 4 && i < nx / 4 + 14 && j >= 1 && j < ny - 1 && k < nz / 3 + 5;
    const bool in_cavity = i >= nx / 4 + 5 && i < nx / 4 + 9 && j >= 4 && j < ny - 4;
    return in_shoe && !in_cavity;
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i)
        if (solid(i - 1, j, k) || solid(i, j, k)) p.ax[i + long(nx + 1) * (j + long(ny) * k)] = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (solid(i, j - 1, k) || solid(i, j, k)) p.ay[i + long(nx) * (j + long(ny + 1) * k)] = 0;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (solid(i, j, k - 1) || solid(i, j, k)) p.az[i + long(nx) * (j + long(ny) * k)] = 0;
}

// Which cells lie in a segment of act.
std::vector<char> covered(const ActiveRows& act, int nx) {
  std::vector<char> in(static_cast<size_t>(act.rows()) * nx, 0);
  for (int r = 0; r < act.rows(); ++r)
    for (int q = act.begin(r); q < act.end(r); ++q)
      for (int i = act.lo(q); i < act.hi(q); ++i) in[long(nx) * r + i] = 1;
  return in;
}

}  // namespace

TEST(ActiveRows, SegmentsMergeShortGapsAndSharesCoverEveryRow) {
  const int nx = 24, ny = 2, nz = 2;
  std::vector<double> d(nx * ny * nz, 0.0);
  for (int i : {2, 3, 4, 5, 15, 16}) d[i] = 1;          // row 0: a gap of 9 cells
  for (int i = 0; i < nx; ++i) d[nx + i] = 1;           // row 1: full
  for (int i : {5, 10}) d[3 * nx + i] = 1;              // row 3: a gap of 4 (row 2 empty)
  ActiveRows a;
  a.from_diag(d.data(), nx, ny, nz, false);
  ASSERT_EQ(a.rows(), 4);
  ASSERT_EQ(a.end(0) - a.begin(0), 2);
  EXPECT_EQ(a.lo(a.begin(0)), 2); EXPECT_EQ(a.hi(a.begin(0)), 6);
  EXPECT_EQ(a.lo(a.begin(0) + 1), 15); EXPECT_EQ(a.hi(a.begin(0) + 1), 17);
  ASSERT_EQ(a.end(1) - a.begin(1), 1);
  EXPECT_EQ(a.lo(a.begin(1)), 0); EXPECT_EQ(a.hi(a.begin(1)), nx);
  EXPECT_EQ(a.end(2), a.begin(2));
  ASSERT_EQ(a.end(3) - a.begin(3), 1);
  EXPECT_EQ(a.lo(a.begin(3)), 5); EXPECT_EQ(a.hi(a.begin(3)), 11);
  EXPECT_EQ(a.cells(), 4 + 2 + nx + 6);
  ActiveRows w;
  w.from_diag(d.data(), nx, ny, nz, true);  // periodic x: whole rows
  EXPECT_EQ(w.cells(), 3 * nx);
  EXPECT_EQ(w.end(2), w.begin(2));
  for (int nth = 1; nth <= 5; ++nth) {
    int next = 0, next_plane = 0;
    for (int t = 0; t < nth; ++t) {
      int r0, r1, k0, k1;
      a.share(t, nth, r0, r1);
      a.share_planes(t, nth, k0, k1);
      EXPECT_EQ(r0, next) << nth << " threads, thread " << t;
      EXPECT_LE(r0, r1);
      EXPECT_EQ(k0, next_plane);
      next = r1, next_plane = k1;
    }
    EXPECT_EQ(next, a.rows());
    EXPECT_EQ(next_plane, nz);
  }
}

// The die-filling-like grid: segments cover every cell with D > 0, and leave out most of the
// blocked ones.
TEST(ActiveRows, SkippingBlockedCellsChangesNoOtherValue) {
  for (const bool periodic_x : {false, true}) {
    std::array<B, 6> bc{B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open};
    if (periodic_x) bc[0] = bc[1] = B::Periodic;
    const int nx = periodic_x ? 64 : 65, ny = 40, nz = 36;  // above kParallelMin cells
    test::Problem p = test::make_problem(nx, ny, nz, bc);
    add_solids(p);
    Poisson7 op(p.g);
    op.set(p.ax, p.ay, p.az);
    const long n = op.n();
    const auto in = covered(op.active(), nx);
    long blocked = 0, skipped = 0;
    for (long c = 0; c < n; ++c) {
      if (op.diag()[c] > 0) ASSERT_TRUE(in[c]) << "active cell " << c << " outside the segments";
      blocked += !(op.diag()[c] > 0);
      skipped += !in[c];
    }
    std::printf("periodic x %d: %ld cells, %ld blocked, %ld skipped, %ld in segments\n", int(periodic_x), n, blocked,
                skipped, op.active().cells());
    if (!periodic_x) EXPECT_GT(skipped, n / 4);

    // A x against the row formula (the same order of terms), every cell.
    const auto x = test::noise(n, 99);
    std::vector<double> y(n, 7.0), r(n, 7.0);
    op.apply(x.data(), y.data());
    op.residual(p.rhs.data(), x.data(), r.data());
    const auto &wx = op.wx(), &wy = op.wy(), &wz = op.wz();
    long bad = 0;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const long c = i + long(nx) * (j + long(ny) * k);
          auto val = [&](int ii, int jj, int kk) {
            if (ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny || kk >= nz) return 0.0;
            return x[ii + long(nx) * (jj + long(ny) * kk)];
          };
          const long fy = i + long(nx) * (j + long(ny + 1) * k);
          double ref = op.diag()[c] * x[c] - wy[fy] * val(i, j - 1, k) - wy[fy + nx] * val(i, j + 1, k) -
                       wz[c] * val(i, j, k - 1) - wz[c + long(nx) * ny] * val(i, j, k + 1);
          const long fx = i + long(nx + 1) * (j + long(ny) * k);
          if (i > 0) ref -= wx[fx] * x[c - 1];
          if (i < nx - 1) ref -= wx[fx + 1] * x[c + 1];
          if (periodic_x && i == 0) ref -= wx[fx] * x[c + nx - 1];
          if (periodic_x && i == nx - 1) ref -= wx[fx - (nx - 1)] * x[c - (nx - 1)];
          bad += y[c] != ref;
          bad += r[c] != p.rhs[c] - ref;
        }
    EXPECT_EQ(bad, 0) << "cells where A x or b - A x differ from the row formula";
    double dot_ref = 0;
    for (int rr = 0; rr < ny * nz; ++rr) {
      double s = 0;
      for (int i = 0; i < nx; ++i) s += x[long(nx) * rr + i] * y[long(nx) * rr + i];
      dot_ref += s;
    }
    std::vector<double> y2(n);
    EXPECT_EQ(op.apply_dot(x.data(), y2.data()), dot_ref);

    // The float smoother, restriction and prolongation with and without skipping, from the
    // same x and b (b = 0 on the blocked cells, as the PCG residual is), for 1 to 3 threads.
    const double scale = stencil32_scale(op);
    GridSpec cg = p.g;
    cg.nx = (nx + 1) / 2, cg.ny = (ny + 1) / 2, cg.nz = (nz + 1) / 2;
    for (const double omega : {1.0, 1.2}) {
      Stencil32 full, skip;
      full.set(op, scale, omega, nullptr);
      skip.set(op, scale, omega, &op.active());
      EXPECT_EQ(full.active().cells(), n);
      std::vector<float> b(n), x0(n), xc(cg.cells());
      const auto nb = test::noise(n, 5), nx0 = test::noise(n, 6), nxc = test::noise(cg.cells(), 8);
      for (long c = 0; c < n; ++c) b[c] = op.diag()[c] > 0 ? float(nb[c]) : 0.0f, x0[c] = float(nx0[c]);
      for (long c = 0; c < cg.cells(); ++c) xc[c] = float(nxc[c]);
      std::vector<float> first_bc;
      std::vector<float> first_x;
      for (int threads = 1; threads <= 3; ++threads) {
        omp_set_num_threads(threads);
        std::vector<float> xf = x0, xs = x0, bcf(cg.cells(), 3.0f), bcs(cg.cells(), 4.0f);
        full.gs_pair(b.data(), xf.data(), 0, true);  // from zero: the first colour does not read x
        skip.gs_pair(b.data(), xs.data(), 0, true);
        for (int s = 0; s < 2; ++s) {
          full.gs_pair(b.data(), xf.data(), 0, false);
          skip.gs_pair(b.data(), xs.data(), 0, false);
        }
        full.restrict_residual(b.data(), xf.data(), cg, bcf.data());
        skip.restrict_residual(b.data(), xs.data(), cg, bcs.data());
        full.prolong_add(cg, xc.data(), xf.data());
        skip.prolong_add(cg, xc.data(), xs.data());
        full.gs_pair(b.data(), xf.data(), 1, false);
        skip.gs_pair(b.data(), xs.data(), 1, false);
        long dx = 0, db = 0;
        for (long c = 0; c < n; ++c) dx += in[c] && xf[c] != xs[c];
        for (long c = 0; c < cg.cells(); ++c) db += bcf[c] != bcs[c];
        EXPECT_EQ(dx, 0) << "omega " << omega << ", " << threads << " threads: cells of x that differ";
        EXPECT_EQ(db, 0) << "omega " << omega << ", " << threads << " threads: coarse residuals that differ";
        if (threads == 1) first_x = xs, first_bc = bcs;
        EXPECT_TRUE(xs == first_x && bcs == first_bc) << threads << " threads against 1";
      }
      omp_set_num_threads(1);
    }

    // The multigrid's z: 0 on every skipped cell, finite everywhere.
    MultigridPreconditioner mg(p.g, 3, MultigridPreconditioner::Precision::Single, MultigridPreconditioner::Cycle::W,
                               1.2);
    mg.setup(op);
    ASSERT_GT(mg.levels(), 2);
    auto rr = test::noise(n, 1234);
    for (long c = 0; c < n; ++c)
      if (!(op.diag()[c] > 0)) rr[c] = 0;
    std::vector<double> z(n, 5.0);
    mg.apply(rr.data(), z.data());
    long nonzero = 0, nonfinite = 0;
    for (long c = 0; c < n; ++c) nonzero += !in[c] && z[c] != 0, nonfinite += !std::isfinite(z[c]);
    EXPECT_EQ(nonzero, 0);
    EXPECT_EQ(nonfinite, 0);
    // The whole cycle (every level but the coarsest skipping) against the one that skips
    // nothing, for 1 to 3 threads: the same z on every cell it computes.
    MultigridPreconditioner mg_all(p.g, 3, MultigridPreconditioner::Precision::Single,
                                   MultigridPreconditioner::Cycle::W, 1.2, false);
    mg_all.setup(op);
    EXPECT_FALSE(mg_all.zero_outside_active());
    for (int threads = 1; threads <= 3; ++threads) {
      omp_set_num_threads(threads);
      std::vector<double> zs(n, 5.0), za(n, 6.0);
      mg.apply(rr.data(), zs.data());
      mg_all.apply(rr.data(), za.data());
      long differ = 0;
      for (long c = 0; c < n; ++c) differ += in[c] && zs[c] != za[c];
      std::printf("  multigrid W(3,3), %d threads: %ld of %ld computed cells differ\n", threads, differ,
                  op.active().cells());
      EXPECT_EQ(differ, 0);
      EXPECT_TRUE(zs == z);
    }
    omp_set_num_threads(1);
    // With z = 0 outside the segments, projecting only the one-cell components inside them
    // gives the whole projection's result.
    EXPECT_TRUE(mg.zero_outside_active());
    std::vector<double> z_all = z;
    op.project_floating(z_all.data());
    op.project_floating(z.data(), true);
    EXPECT_TRUE(z == z_all);
  }
}

// SUNDIALS PCG with its vector operations on the active segments against the same PCG on every
// cell (the multigrid preconditioner of the cases, pcg-mgw3's cycle): the same iterations and
// the same phi on every active cell, bit for bit, for 1 and 2 threads.
TEST(ActiveRows, SundialsPcgOnTheSegmentsIsThePcgOnEveryCell) {
  const std::array<B, 6> bc{B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open};
  const int nx = 65, ny = 40, nz = 36;
  test::Problem p = test::make_problem(nx, ny, nz, bc);
  add_solids(p);
  Poisson7 op(p.g);
  op.set(p.ax, p.ay, p.az);
  const long n = op.n();
  MultigridPreconditioner mg(p.g, 3, MultigridPreconditioner::Precision::Single, MultigridPreconditioner::Cycle::W,
                             1.2);
  mg.setup(op);
  auto apply = [&](const double* x, double* y) { op.apply(x, y); };
  auto prec = [&](const double* r, double* z) {
    mg.apply(r, z);
    op.project_floating(z, true);
  };
  SundialsPcg seg(n, apply, prec, &op.active(), nx), all(n, apply, prec);
  std::vector<double> b(n);
  for (long c = 0; c < n; ++c) b[c] = -p.rhs[c];
  op.project_floating(b.data());
  const double tol = 1e-9 * std::sqrt(dot(b.data(), b.data(), n));
  const auto in = covered(op.active(), nx);
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    for (const bool zero_guess : {true, false}) {
      std::vector<double> xs(n, 0.0), xa(n, 0.0);
      if (!zero_guess) {
        const auto g = test::noise(n, 31);
        for (long c = 0; c < n; ++c) xs[c] = xa[c] = 0.01 * g[c];
      }
      const auto rs = seg.solve(b.data(), xs.data(), tol, 200, zero_guess);
      const auto ra = all.solve(b.data(), xa.data(), tol, 200, zero_guess);
      ASSERT_TRUE(rs.converged && ra.converged);
      EXPECT_EQ(rs.iterations, ra.iterations);
      EXPECT_EQ(rs.res_norm, ra.res_norm);
      long differ = 0;
      for (long c = 0; c < n; ++c) differ += in[c] && xs[c] != xa[c];
      std::printf("%d threads, zero guess %d: %d iterations, %ld active cells differ\n", threads, int(zero_guess),
                  rs.iterations, differ);
      EXPECT_EQ(differ, 0);
    }
  }
  omp_set_num_threads(1);
}

// Poisson7::set() keeps its arrays from call to call and writes every weight, diagonal and
// Open entry without filling them first. Checked: an operator set four times (three solid
// patterns, then the last one's coefficients scaled, which keeps the pattern) gives, after
// each set, exactly what a fresh operator set once with the same coefficients gives: the
// diagonal, A x for a varied x, the floating components and their projection, the active
// segments. Open sides at -x and +z (their terms go to the diagonal), and a periodic x and y
// variant (the wrapped faces), on 1 and 2 threads.
TEST(Poisson7Set, ReusedArraysGiveWhatAFreshOperatorGives) {
  long compared = 0, differ = 0;
  for (const bool periodic : {false, true}) {
    std::array<B, 6> bc{B::Open, B::Wall, B::Wall, B::Wall, B::Wall, B::Open};
    if (periodic) bc[0] = bc[1] = bc[2] = bc[3] = B::Periodic;
    const int nx = 64, ny = 40, nz = 36;  // above kParallelMin cells
    for (const int threads : {1, 2}) {
      omp_set_num_threads(threads);
      Poisson7 kept(test::make_problem(nx, ny, nz, bc).g);
      for (int round = 0; round < 4; ++round) {
        test::Problem p = test::make_problem(nx, ny, nz, bc);
        // the solids shifted by 0, 1 and 2 cells along x and y; round 3 keeps round 2's
        // pattern with the coefficients scaled
        const int shift = std::min(round, 2);
        test::Problem q = p;
        add_solids(q);
        auto moved = [&](std::vector<double>& a, const std::vector<double>& src, int ex, int ey) {
          const long rows = static_cast<long>(a.size()) / ex;
          for (long r = 0; r < rows; ++r)
            for (int i = 0; i < ex; ++i) {
              const long row_src = (r % ey + ey - shift) % ey + (r / ey) * ey;
              a[r * ex + i] = src[row_src * ex + (i + ex - shift) % ex];
            }
        };
        moved(p.ax, q.ax, nx + 1, ny);
        moved(p.ay, q.ay, nx, ny + 1);
        moved(p.az, q.az, nx, ny);
        if (round == 3)
          for (auto* a : {&p.ax, &p.ay, &p.az})
            for (double& v : *a) v *= 1.7;
        kept.set(p.ax, p.ay, p.az);
        Poisson7 fresh(p.g);
        fresh.set(p.ax, p.ay, p.az);
        const long n = fresh.n();
        for (long c = 0; c < n; ++c) differ += kept.diag()[c] != fresh.diag()[c];
        std::vector<double> x(n), yk(n), yf(n), vk(n), vf(n);
        for (long c = 0; c < n; ++c) x[c] = std::sin(0.37 * c) + 0.01 * (c % 13), vk[c] = vf[c] = std::cos(0.11 * c);
        kept.apply(x.data(), yk.data());
        fresh.apply(x.data(), yf.data());
        kept.project_floating(vk.data());
        fresh.project_floating(vf.data());
        for (long c = 0; c < n; ++c) differ += (yk[c] != yf[c]) + (vk[c] != vf[c]);
        differ += kept.floating_components() != fresh.floating_components();
        differ += !(kept.active() == fresh.active());
        compared += 3 * n + 2;
        EXPECT_GT(fresh.floating_components(), 0);
      }
    }
  }
  omp_set_num_threads(omp_get_num_procs());
  std::printf("[ Poisson7 set ] %ld values compared over 16 sets, %ld differ (tolerance: 0, bit for bit)\n",
              compared, differ);
  EXPECT_EQ(differ, 0);
}
