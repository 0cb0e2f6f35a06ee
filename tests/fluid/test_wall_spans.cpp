// The explicit terms, the predictor and the correction pass over the faces at the ends of
// each row that lie wholly inside walls (FluidSolver::spans_, fluid_solver.hpp). That must
// change no bit of the state: a face outside its row's span has alpha = 1 and a wall
// velocity that is not -0, so u* = (1 - 1) u_hat + U_B = U_B whatever u_hat, and every flux
// a face inside a span needs is still evaluated, at the same position with the same
// operations. The threads share the planes by the work in the spans, which must not matter.
//
// The set-up is shaped like the die filling: a table (a slab with a hole) under a moving
// shoe of two walls, on a grid whose x rows run through both; one shoe wall moves with a
// velocity whose y part is -0 (its v faces must then be evaluated), an eps that varies,
// drag sources, Heun with van Leer and viscosity. Steps with and without the skipping,
// on 1, 2 and 3 threads, are compared bit for bit (signs of zero included) on every slot
// of u, v, w and p.
#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace cgdem::fluid::test {
namespace {

// Slots (ghosts included) whose bits differ.
long bit_differences(const Field& a, const Field& b) {
  if (a.extent() != b.extent()) return -1;
  long n = 0;
  for (int k = -kGhost; k < a.nk() + kGhost; ++k)
    for (int j = -kGhost; j < a.nj() + kGhost; ++j)
      for (int i = -kGhost; i < a.ni() + kGhost; ++i)
        n += std::bit_cast<std::uint64_t>(a.data()[a.index(i, j, k)]) !=
             std::bit_cast<std::uint64_t>(b.data()[b.index(i, j, k)]);
  return n;
}

struct SpanRun {
  FluidState s;
  std::array<long, 3> skipped{};
  long minus_zero_walls = 0;  // v faces with alpha = 1 and U_B = -0
};

SpanRun run(bool skip, int threads, int steps) {
  const int nx = 48, ny = 32, nz = 24;  // > kOmpMinWork cells: the loops run on the threads
  const double dx = 1e-3;
  MacGrid g{nx, ny, nz, dx, {0, 0, 0}};
  FluidParams p;
  p.rho = 1.2;
  p.mu = 1.8e-5;
  p.bc = uniform_boundary(BcType::Wall);
  p.bc[5].type = BcType::Open;
  p.pressure.rel_tol = 1e-9;
  geometry::Scene scene;
  const int fixed = scene.add_body("fixed", geometry::Motion::constant({0, 0, 0}));
  const double big = 1.0, top = 8.5e-3;  // the table top off the grid planes: sampled faces
  scene.add_part(fixed, "table",
                 geometry::make_difference(geometry::make_box({-big, -big, -big}, {big, big, top}),
                                           geometry::make_box({19e-3, 6e-3, 3e-3}, {31e-3, 26e-3, 1.0})));
  // Thin plates across whole rows, with air on both sides: a row passed over between two
  // rows evaluated, in y (the wall) and in z (the shelf).
  scene.add_part(fixed, "wall", geometry::make_box({-big, 19.9e-3, top}, {big, 22.1e-3, 17e-3}));
  scene.add_part(fixed, "shelf", geometry::make_box({-big, 0.5e-3, 13.9e-3}, {big, 9e-3, 16.1e-3}));
  const int shoe = scene.add_body("shoe", geometry::Motion::constant({0.4, 0, 0}));
  scene.add_part(shoe, "shoe left", geometry::make_box({7e-3, 4e-3, top}, {14.3e-3, 28e-3, 19e-3}));
  // At the +x end of the rows, moving with a y velocity of -0: its v faces are not passed over.
  const int shoe2 = scene.add_body("shoe right", geometry::Motion::constant({0.4, -0.0, 0}));
  scene.add_part(shoe2, "shoe right", geometry::make_box({38.2e-3, 4e-3, top}, {big, 28e-3, 19e-3}));
  omp_set_num_threads(threads);
  FluidSolver solver(g, p);
  solver.set_skip_walls(skip);
  SpanRun r;
  r.s = make_fluid_state(g);
  FluidState& s = r.s;
  const double L = nx * dx;
  auto swirl = [&](const Vec3& x, int c) {
    const double a = std::sin(7.0 * x.x / L + 1.3 * c), b = std::cos(5.0 * x.y / L - 0.4 * c),
                 e = std::sin(3.0 * x.z / L + 0.7);
    return 0.3 * a * b * e + (c == 2 ? -0.05 : 0.02);
  };
  set_faces(g, s.u, 0, [&](const Vec3& x) { return swirl(x, 0); });
  set_faces(g, s.v, 1, [&](const Vec3& x) { return swirl(x, 1); });
  set_faces(g, s.w, 2, [&](const Vec3& x) { return swirl(x, 2); });
  auto eps_at = [&](const Vec3& x, double t) {
    return 0.55 + 0.4 * std::fabs(std::sin(11.0 * x.x / L + 60 * t) * std::cos(9.0 * x.y / L - 4.0 * x.z / L));
  };
  set_cells(g, s.eps_old, [&](const Vec3& x) { return eps_at(x, 0); });
  Sources src;
  for (int d = 0; d < 3; ++d) {
    src.K[d] = make_face_field(g, d);
    src.Kv[d] = make_face_field(g, d);
    set_faces(g, src.K[d], d, [&](const Vec3& x) { return x.z < 14e-3 && x.x > 17e-3 ? 3e3 : 0.0; });
    set_faces(g, src.Kv[d], d, [&](const Vec3& x) { return x.z < 14e-3 && x.x > 17e-3 ? -0.2e3 * (d + 1) : 0.0; });
  }
  const double dt = 2e-4;
  for (int n = 0; n < steps; ++n) {
    set_cells(g, s.eps, [&](const Vec3& x) { return eps_at(x, s.t + dt); });
    const StepStats st = solver.advance(s, scene.at(s.t + dt), src, dt);
    EXPECT_TRUE(st.pressure_converged);
  }
  for (int d = 0; d < 3; ++d) r.skipped[d] = solver.faces_in_walls(d);
  const Field &al = solver.ibm().alpha_face[1], &ub = solver.ibm().ub_face[1];
  for (int k = 0; k < al.nk(); ++k)
    for (int j = 0; j < al.nj(); ++j)
      for (int i = 0; i < al.ni(); ++i)
        r.minus_zero_walls += al(i, j, k) == 1.0 && ub(i, j, k) == 0 && std::signbit(ub(i, j, k));
  return r;
}

TEST(WallSpans, SkippingTheFacesInsideWallsChangesNoBit) {
  const int steps = 6;
  const SpanRun ref = run(false, 1, steps);
  const long faces = 49L * 32 * 24;  // per component, about
  for (int threads : {1, 2, 3}) {
    const SpanRun r = run(true, threads, steps);
    const long du = bit_differences(r.s.u, ref.s.u), dv = bit_differences(r.s.v, ref.s.v),
               dw = bit_differences(r.s.w, ref.s.w), dp = bit_differences(r.s.p, ref.s.p);
    std::printf("[ wall spans ] %d thread(s): faces passed over u %ld, v %ld, w %ld (of about %ld each); "
                "v faces inside walls with U_B = -0: %ld; slots differing from the run without skipping: "
                "u %ld, v %ld, w %ld, p %ld (tol 0)\n",
                threads, r.skipped[0], r.skipped[1], r.skipped[2], faces, r.minus_zero_walls, du, dv, dw, dp);
    EXPECT_EQ(du, 0);
    EXPECT_EQ(dv, 0);
    EXPECT_EQ(dw, 0);
    EXPECT_EQ(dp, 0);
    // The test means something only if much is skipped and the -0 walls are there.
    for (int d = 0; d < 3; ++d) EXPECT_GT(r.skipped[d], faces / 4);
    EXPECT_GT(r.minus_zero_walls, 100);
  }
}

}  // namespace
}  // namespace cgdem::fluid::test
