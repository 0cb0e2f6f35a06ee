// The IBM fractions updated near the moving bodies only (static cache + region, ibm.cpp) must
// equal a full evaluation with Scene::Frame::solid_fraction / wall_velocity on every box, on
// the die-filling geometry (static table and stepped die, moving shoe), step after step and
// after a jump of the shoe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid/ibm.hpp"
#include "geometry/die_filling.hpp"
#include "geometry/shape.hpp"

namespace cgdem::fluid::test {
namespace {

// The reference: every box of every array through the Scene API (n^3 midpoint samples).
void reference(const MacGrid& g, const geometry::Scene::Frame& f, int n, IbmFractions& r) {
  const double h = 0.5 * g.dx;
  r.alpha_cell = make_cell_field(g);
  for (int a = 0; a < 4; ++a) {
    Field& al = a == 0 ? r.alpha_cell : r.alpha_face[a - 1];
    if (a > 0) al = make_face_field(g, a - 1), r.ub_face[a - 1] = make_face_field(g, a - 1);
    for (int k = 0; k < al.nk(); ++k)
      for (int j = 0; j < al.nj(); ++j)
        for (int i = 0; i < al.ni(); ++i) {
          const Vec3 x = a == 0 ? g.cell_centre(i, j, k) : g.face_centre(a - 1, i, j, k);
          al(i, j, k) = f.solid_fraction(x - Vec3{h, h, h}, x + Vec3{h, h, h}, n);
          if (a > 0 && al(i, j, k) > 0) r.ub_face[a - 1](i, j, k) = f.wall_velocity(x)[a - 1];
        }
  }
}

long mismatches(const Field& a, const Field& b) {
  long m = 0;
  for (int k = 0; k < a.nk(); ++k)
    for (int j = 0; j < a.nj(); ++j)
      for (int i = 0; i < a.ni(); ++i) m += a(i, j, k) != b(i, j, k);
  return m;
}

TEST(IbmCache, MovingShoeEqualsFullEvaluation) {
  geometry::DieFillingParams dp;
  geometry::Scene scene;
  geometry::add_die_filling(scene, dp);
  MacGrid g{70, 35, 25, 1.2e-3, {0, 0, 0}};
  IbmFractions inc;
  long total = 0;
  // Steps of 1e-4 s (10 um of travel), then a jump of 20 ms (2 mm) and one more step.
  for (double t : {0.1, 0.1001, 0.1002, 0.1202, 0.1203}) {
    const auto f = scene.at(t);
    EXPECT_TRUE(update_ibm(g, f, 3, inc));
    IbmFractions ref;
    reference(g, f, 3, ref);
    long m = mismatches(inc.alpha_cell, ref.alpha_cell);
    for (int d = 0; d < 3; ++d) m += mismatches(inc.alpha_face[d], ref.alpha_face[d]) + mismatches(inc.ub_face[d], ref.ub_face[d]);
    std::printf("[ ibm ] t = %.4f s: %ld boxes sub-sampled near the shoe, %ld values differ from the full evaluation\n", t,
                inc.sampled_faces, m);
    EXPECT_EQ(m, 0);
    EXPECT_TRUE(inc.any_solid);
    total += m;
  }
  EXPECT_FALSE(update_ibm(g, scene.at(0.1203), 3, inc));  // nothing moved
}

// Boxes are sampled axis by axis (Shape::axis_separable), other parts sample by sample: a
// scene that mixes them (box, cylinder, half-space, a CSG difference, a moving box that
// overlaps them) must give the full evaluation's counts, for 4 and 5 samples per axis.
TEST(IbmCache, BoxesTestedAxisByAxisEqualSampleBySample) {
  geometry::Scene scene;
  const int fixed = scene.add_body("fixed", geometry::Motion{});
  scene.add_part(fixed, "floor", geometry::make_half_space({0, 0, 1.3e-3}, {0.1, 0, 1}));
  scene.add_part(fixed, "block", geometry::make_box({2.9e-3, -1, 1e-3}, {5.35e-3, 2.2e-3, 4.1e-3}));
  scene.add_part(fixed, "post", geometry::make_cylinder({9.3e-3, 2.1e-3, 0}, {9.3e-3, 2.1e-3, 6e-3}, 1.1e-3));
  scene.add_part(fixed, "frame", geometry::make_difference(geometry::make_box({11e-3, 0.5e-3, 2e-3}, {14.2e-3, 4e-3, 5.5e-3}),
                                                           geometry::make_box({11.7e-3, 1.3e-3, 1e-3}, {13.5e-3, 3.1e-3, 6e-3})));
  const int moving = scene.add_body("moving", geometry::Motion::constant({0.9, 0, 0}));
  scene.add_part(moving, "slider", geometry::make_box({-1.7e-3, 0.35e-3, 1.1e-3}, {0.6e-3, 3.3e-3, 3.7e-3}));
  MacGrid g{28, 8, 12, 0.6e-3, {0, 0, 0}};
  for (int n : {4, 5}) {
    IbmFractions inc;
    for (double t : {0.0, 0.004, 0.0047, 0.011}) {
      const auto f = scene.at(t);
      update_ibm(g, f, n, inc);
      IbmFractions ref;
      reference(g, f, n, ref);
      long m = mismatches(inc.alpha_cell, ref.alpha_cell);
      for (int d = 0; d < 3; ++d) m += mismatches(inc.alpha_face[d], ref.alpha_face[d]);
      std::printf("[ ibm ] n = %d, t = %.4f s: %ld boxes sub-sampled, %ld values differ from the full evaluation\n", n, t,
                  inc.sampled_faces, m);
      EXPECT_EQ(m, 0);
      EXPECT_GT(inc.sampled_faces, 500);
    }
  }
}

}  // namespace
}  // namespace cgdem::fluid::test
