// The ring (geometry/ring.cpp) against closed forms: the distances to its faces, to the hole's
// wall and to the hole's rim circle (where the difference box minus cylinder gives only a
// bound), and against that difference wherever the difference is exact (a face nearest).
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shape.hpp"

namespace cgdem::geometry {
namespace {

// A floor plate 0.5 thick with a hole of radius 1 about the z axis, outer radius 4.
constexpr double kT = 0.5, kRi = 1.0, kRo = 4.0;

TEST(Ring, ClosedFormsAtFacesHoleAndRim) {
  const ShapePtr ring = make_ring({0, 0, 0}, {0, 0, kT}, kRi, kRo);
  struct Case {
    const char* what;
    Vec3 x;
    double want;
  };
  const double s = std::sqrt(0.5);
  const Case cases[] = {
      {"above the top face", {2.5, 0, 0.8}, 0.3},
      {"below the bottom face", {0, -2, -0.25}, 0.25},
      {"inside, the top face nearest", {2.0, 0, 0.4}, -0.1},
      {"inside, the hole's wall nearest", {0, 1.05, 0.25}, -0.05},
      {"in the hole, on its mid-plane", {0.4, 0, 0.25}, 0.6},
      {"on the axis", {0, 0, 0.25}, 1.0},
      {"above the rim, diagonal", {0.7 * s, 0.7 * s, kT + 0.4}, 0.5},  // (0.3, 0.4) from the rim
      {"below the rim", {-0.88, 0, -0.09}, std::hypot(0.12, 0.09)},
      {"beyond the outer rim", {0, 4.3, 0.9}, 0.5},
  };
  for (const Case& k : cases) {
    Vec3 g;
    const double d = ring->distance_gradient(k.x, g);
    std::printf("[ ring ] %-32s d = %+.15f (closed form %+.15f, err %.1e; tol 1e-14), |grad| = %.15f\n", k.what, d,
                k.want, std::fabs(d - k.want), norm(g));
    EXPECT_NEAR(d, k.want, 1e-14) << k.what;
    EXPECT_NEAR(norm(g), 1.0, 1e-14) << k.what;
  }
  // Above the rim the gradient points from the rim circle to the point.
  Vec3 g;
  ring->distance_gradient({0.7, 0, kT + 0.4}, g);
  EXPECT_NEAR(g.x, -0.6, 1e-14);
  EXPECT_NEAR(g.z, 0.8, 1e-14);
}

TEST(Ring, AgreesWithCylinderDifferenceWhereThatIsExact) {
  const ShapePtr ring = make_ring({0, 0, 0}, {0, 0, kT}, kRi, kRo);
  const ShapePtr diff = make_difference(make_cylinder({0, 0, 0}, {0, 0, kT}, kRo), make_cylinder({0, 0, -1}, {0, 0, kT + 1}, kRi));
  double worst = 0, worst_rim = 0;
  int exact = 0, rim = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 x{-5 + 10 * std::fmod(0.618034 * k, 1.0), -5 + 10 * std::fmod(0.414214 * k, 1.0),
                 -1 + 2.5 * std::fmod(0.732051 * k, 1.0)};
    const double rho = std::hypot(x.x, x.y);
    const double dr = ring->distance(x), dd = diff->distance(x);
    // The difference is exact where the nearest point is on a face, not a rim: inside the solid,
    // or outside with the point over a face (kRi < rho < kRo) or in the hole between the faces.
    const bool face = dr < 0 || (rho > kRi && rho < kRo) || (x.z > 0 && x.z < kT && rho < kRi);
    if (face) {
      ++exact;
      worst = std::max(worst, std::fabs(dr - dd));
    } else if (rho < kRi) {  // above or below the hole: the max is a bound from below
      ++rim;
      worst_rim = std::max(worst_rim, dr - dd);
      EXPECT_GE(dr, dd - 1e-14);
    }
  }
  std::printf("[ ring ] against cylinder minus cylinder: %d points where that is exact, worst %.1e (tol 1e-14); %d by "
              "the hole's rims, where it falls short by up to %.3f\n",
              exact, worst, rim, worst_rim);
  EXPECT_LT(worst, 1e-14);
  EXPECT_GT(worst_rim, 0.1);  // the reason for the ring: the difference is not the distance there
}

}  // namespace
}  // namespace cgdem::geometry
