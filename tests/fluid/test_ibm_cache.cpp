// The IBM fractions updated near the moving bodies only (static cache + region, ibm.cpp) must
// equal a full evaluation with Scene::Frame::solid_fraction / wall_velocity on every box, on
// the die-filling geometry (static table and stepped die, moving shoe), step after step and
// after a jump of the shoe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <bit>
#include <cstdint>
#include <vector>

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

// Slots whose bits differ (signs of zero included).
long bit_mismatches(const Field& a, const Field& b) {
  long m = 0;
  for (int k = 0; k < a.nk(); ++k)
    for (int j = 0; j < a.nj(); ++j)
      for (int i = 0; i < a.ni(); ++i) m += std::bit_cast<std::uint64_t>(a(i, j, k)) != std::bit_cast<std::uint64_t>(b(i, j, k));
  return m;
}

long bit_mismatches(const IbmFractions& a, const IbmFractions& b) {
  long m = bit_mismatches(a.alpha_cell, b.alpha_cell);
  for (int d = 0; d < 3; ++d) m += bit_mismatches(a.alpha_face[d], b.alpha_face[d]) + bit_mismatches(a.ub_face[d], b.ub_face[d]);
  return m;
}

// The boxes kept while the moving bodies travel less than their clearance (ibm.hpp) must
// give the bits of evaluating every box of the region, call after call: the die filling
// (one moving body, so boxes inside the shoe are kept too) from rest through the shoe's
// ramp in steps of 20 um, then a jump back; and a scene of two moving bodies of other
// shapes (cylinder, CSG frame, sphere) that turn back, where only the boxes outside every
// moving part are kept; a block moving through a static one. Every few calls the fractions are also checked against the full
// evaluation.
TEST(IbmCache, KeptBoxesEqualEvaluatingEveryBox) {
  struct Case {
    const char* name;
    geometry::Scene scene;
    MacGrid g;
    std::vector<double> times;
  };
  std::vector<Case> cases(3);
  {
    Case& c = cases[0];
    c.name = "die filling";
    geometry::add_die_filling(c.scene, geometry::DieFillingParams{});
    c.g = MacGrid{70, 35, 25, 1.2e-3, {0, 0, 0}};
    for (int n = 0; n <= 40; ++n) c.times.push_back(2e-4 * n);  // the ramp ends at 1 ms
    c.times.push_back(0.003);                                     // a jump back
  }
  {
    Case& c = cases[1];
    c.name = "two moving bodies";
    const int fixed = c.scene.add_body("fixed", geometry::Motion{});
    c.scene.add_part(fixed, "floor", geometry::make_half_space({0, 0, 1.3e-3}, {0.1, 0, 1}));
    c.scene.add_part(fixed, "block", geometry::make_box({2.9e-3, -1, 1e-3}, {5.35e-3, 2.2e-3, 4.1e-3}));
    const int a = c.scene.add_body("a", geometry::Motion({0.0, 0.004}, {{0.5, 0.1, 0}, {-0.5, 0.2, 0}}));
    c.scene.add_part(a, "post", geometry::make_cylinder({6.3e-3, 2.1e-3, 0}, {6.3e-3, 2.1e-3, 6e-3}, 1.6e-3));
    c.scene.add_part(a, "frame", geometry::make_difference(geometry::make_box({11e-3, 0.5e-3, 2e-3}, {15.2e-3, 4.6e-3, 5.5e-3}),
                                                           geometry::make_box({11.7e-3, 1.3e-3, 1e-3}, {13.5e-3, 3.1e-3, 6e-3})));
    const int b = c.scene.add_body("b", geometry::Motion::constant({-0.3, 0, 0.05}));
    c.scene.add_part(b, "ball", geometry::make_sphere({9e-3, 2.5e-3, 3e-3}, 1.9e-3));
    c.g = MacGrid{40, 10, 14, 0.45e-3, {0, 0, 0}};
    for (int n = 0; n <= 40; ++n) c.times.push_back(2e-4 * n);  // body a turns back at 2 ms
  }
  {
    Case& c = cases[2];
    c.name = "a moving block through a static one";  // deep inside both: the nearer surface's velocity
    const int fixed = c.scene.add_body("fixed", geometry::Motion{});
    c.scene.add_part(fixed, "pillar", geometry::make_box({8e-3, -1, -1}, {11e-3, 1, 1}));
    const int m = c.scene.add_body("slider", geometry::Motion::constant({1.0, 0, 0}));
    c.scene.add_part(m, "slider", geometry::make_box({1e-3, 0.9e-3, 1.1e-3}, {7e-3, 5.2e-3, 5.3e-3}));
    c.g = MacGrid{40, 10, 10, 0.6e-3, {0, 0, 0}};
    for (int n = 0; n <= 40; ++n) c.times.push_back(2e-4 * n);  // 8 mm of travel
  }
  for (Case& c : cases) {
    IbmFractions kept, every;
    every.keep_far = false;
    long kept_total = 0, worst = 0, worst_ref = 0;
    for (size_t n = 0; n < c.times.size(); ++n) {
      const auto f = c.scene.at(c.times[n]);
      update_ibm(c.g, f, 3, kept);
      update_ibm(c.g, f, 3, every);
      kept_total += kept.kept_boxes;
      const long m = bit_mismatches(kept, every);
      worst = std::max(worst, m);
      EXPECT_EQ(m, 0) << c.name << ", t = " << c.times[n];
      if (n % 10 == 0 || n + 1 == c.times.size()) {
        IbmFractions ref;
        reference(c.g, f, 3, ref);
        long mr = mismatches(kept.alpha_cell, ref.alpha_cell);
        for (int d = 0; d < 3; ++d) mr += mismatches(kept.alpha_face[d], ref.alpha_face[d]) + mismatches(kept.ub_face[d], ref.ub_face[d]);
        worst_ref = std::max(worst_ref, mr);
        EXPECT_EQ(mr, 0) << c.name << ", t = " << c.times[n];
      }
    }
    std::printf("[ ibm ] %s: %zu calls, %ld boxes kept in all (last call %ld, %ld sub-sampled); values differing from "
                "evaluating every box: at most %ld, from the full evaluation: at most %ld (tol 0)\n",
                c.name, c.times.size(), kept_total, kept.kept_boxes, kept.sampled_faces, worst, worst_ref);
    EXPECT_GT(kept_total, 10000);  // the test means something only if boxes were kept
    // Switched off and on again between calls: the kept state starts afresh.
    for (bool on : {false, true}) {
      const auto f = c.scene.at(c.times.back() + (on ? 4e-4 : 2e-4));
      kept.keep_far = on;
      update_ibm(c.g, f, 3, kept);
      update_ibm(c.g, f, 3, every);
      EXPECT_EQ(bit_mismatches(kept, every), 0) << c.name << ", keep_far " << on;
    }
  }
}

}  // namespace
}  // namespace cgdem::fluid::test
