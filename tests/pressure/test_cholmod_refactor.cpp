// CholmodFactor::refactor keeps the analysis (fill-reducing order, symbolic factor) when only
// the values of the operator's coefficients change, as from one fluid step to the next on the
// multigrid's coarsest level. It must give the same factor as a new factorisation, to the bit,
// and analyse anew when the pattern changes (a face closed by a wall). Reference: a new
// CholmodFactor of the same operator; the solve is also checked against the operator itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "mms.hpp"
#include "solvers/pressure/cholmod_factor.hpp"

using namespace cgdem::pressure;
using B = Boundary;

namespace {

double uniform(std::uint64_t& s) {
  s ^= s << 13, s ^= s >> 7, s ^= s << 17;
  return double(s >> 11) / double(1ull << 53);
}

// A right-hand side with zero mean on every floating component (where A x = b has solutions).
std::vector<double> rhs(const Poisson7& op) {
  const long n = op.n();
  std::vector<double> b(n), sum(op.floating_components(), 0.0);
  std::vector<long> count(op.floating_components(), 0);
  std::uint64_t s = 99;
  for (auto& v : b) v = uniform(s) - 0.5;
  for (long c = 0; c < n; ++c)
    if (const int q = op.floating_id()[c]; q >= 0) sum[q] += b[c], ++count[q];
  for (long c = 0; c < n; ++c)
    if (const int q = op.floating_id()[c]; q >= 0) b[c] -= sum[q] / count[q];
  return b;
}

struct Counts {
  long differ = 0;
  double residual = 0, change = 0;  // max |A x - b| / max |b|; max |x - x_before| / max |x|
};

// Solves A x = b (b mean-free, so floating components are consistent) with `f` and with a new
// factor of op, and compares.
Counts check(CholmodFactor& f, const Poisson7& op, const std::vector<double>& x_before) {
  const long n = op.n();
  std::vector<double> b = rhs(op), x(n), y(n), ax(n);
  f.solve(b.data(), x.data());
  CholmodFactor fresh(op);
  fresh.solve(b.data(), y.data());
  Counts c;
  double bmax = 0, xmax = 0;
  op.apply(x.data(), ax.data());
  for (long q = 0; q < n; ++q) {
    c.differ += x[q] != y[q];
    c.residual = std::max(c.residual, std::abs(ax[q] - b[q]));
    bmax = std::max(bmax, std::abs(b[q]));
    xmax = std::max(xmax, std::abs(x[q]));
    if (!x_before.empty()) c.change = std::max(c.change, std::abs(x[q] - x_before[q]));
  }
  c.residual /= bmax;
  c.change /= xmax;
  return c;
}

std::vector<double> solution(CholmodFactor& f, const Poisson7& op) {
  const std::vector<double> b = rhs(op);
  std::vector<double> x(op.n());
  f.solve(b.data(), x.data());
  return x;
}

void run(const char* name, std::array<B, 6> bc) {
  test::Problem p = test::make_problem(18, 14, 10, bc);
  for (long f = 0; f < long(p.ax.size()); f += 7) p.ax[f] = 0;  // faces closed by walls
  Poisson7 op(p.g);
  op.set(p.ax, p.ay, p.az);
  CholmodFactor f(op);
  // Gives op the coefficients now in p, refactorises f and checks it against a new factor.
  // The solution must also move: then the new numbers were factorised (the old factor would
  // not solve this system).
  auto refactor_and_check = [&](const char* what, bool want_kept) {
    const auto before = solution(f, op);
    op.set(p.ax, p.ay, p.az);
    const bool kept = f.refactor(op);
    const Counts c = check(f, op, before);
    std::printf("[ refactor ] %-9s %s: analysis kept %d, %ld values differ from a new factor, residual %.1e, "
                "solution moved by %.2f of its size\n", name, what, kept, c.differ, c.residual, c.change);
    EXPECT_EQ(kept, want_kept);
    EXPECT_EQ(c.differ, 0);
    EXPECT_LT(c.residual, 1e-10);
    EXPECT_GT(c.change, 1e-3);
  };

  // New values, same pattern: every open face's coefficient scaled by a factor in [0.5, 2).
  std::uint64_t s = 4242;
  for (auto* a : {&p.ax, &p.ay, &p.az})
    for (double& v : *a) v *= 0.5 + 1.5 * uniform(s);
  refactor_and_check("new values", true);
  // A changed pattern: more faces closed.
  for (long q = 3; q < long(p.ay.size()); q += 5) p.ay[q] = 0;
  refactor_and_check("new pattern", false);
}

}  // namespace

TEST(CholmodRefactor, SameFactorAsANewOneToTheBit) {
  run("wall/open", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Open});
  run("walls", {B::Wall, B::Wall, B::Wall, B::Wall, B::Wall, B::Wall});  // floating: one pinned cell
  run("periodic", {B::Periodic, B::Periodic, B::Wall, B::Wall, B::Wall, B::Open});
}
