// The capped cone (geometry/cone.cpp) against closed forms: equal radii give the cylinder's
// distance; on the axis, the distances to the caps, to the apex and to the slanted side
// (R(t) L / sqrt(L^2 + (r1 - r0)^2) from an inner axis point); off the axis, beyond the
// rim, the distance to the rim circle.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shape.hpp"

namespace cgdem::geometry {
namespace {

TEST(Cone, EqualRadiiIsTheCylinder) {
  const Vec3 p0{0.1, -0.2, 0.3}, p1{0.5, 0.7, 1.9};
  const ShapePtr cone = make_cone(p0, p1, 0.4, 0.4), cyl = make_cylinder(p0, p1, 0.4);
  double worst = 0, worst_g = 0;
  for (int k = 0; k < 5000; ++k) {
    const Vec3 x{-1.5 + 3 * std::fmod(0.618034 * k, 1.0), -1.5 + 3 * std::fmod(0.414214 * k, 1.0),
                 -1 + 4 * std::fmod(0.732051 * k, 1.0)};
    Vec3 ga, gb;
    worst = std::max(worst, std::fabs(cone->distance_gradient(x, ga) - cyl->distance_gradient(x, gb)));
    worst_g = std::max(worst_g, norm(ga - gb));
  }
  std::printf("[ cone ] radii 0.4, 0.4 against the cylinder: distance worst %.1e, gradient worst %.1e (tol 1e-14, "
              "1e-12)\n",
              worst, worst_g);
  EXPECT_LT(worst, 1e-14);
  EXPECT_LT(worst_g, 1e-12);
}

TEST(Cone, ClosedFormsOnAndOffTheAxis) {
  const double L = 2, r0 = 1, r1 = 0.25;  // a hopper-like frustum along z
  const ShapePtr c = make_cone({0, 0, 0}, {0, 0, L}, r0, r1), apex = make_cone({0, 0, 0}, {0, 0, L}, r0, 0);
  const double cosine = L / std::hypot(L, r1 - r0);  // the side's normal against the radial direction
  struct Case {
    const char* what;
    const Shape* s;
    Vec3 x;
    double want;
  };
  const Case cases[] = {
      {"below the base, on the axis", c.get(), {0, 0, -0.3}, 0.3},
      {"above the top cap, on the axis", c.get(), {0, 0, L + 0.2}, 0.2},
      {"inside near the base", c.get(), {0, 0, 0.1}, -0.1},
      {"inside, the side nearest", c.get(), {0, 0, 1.5}, -(r0 + (r1 - r0) * 0.75) * cosine},
      {"above the apex, on the axis", apex.get(), {0, 0, L + 0.5}, 0.5},
      {"beyond the base rim, in its plane", c.get(), {1.7, 0, 0}, 0.7},
      {"below the base rim", c.get(), {0, 1.3, -0.4}, 0.5},  // (0.3, 0.4) from the rim
  };
  for (const Case& k : cases) {
    Vec3 g;
    const double d = k.s->distance_gradient(k.x, g);
    std::printf("[ cone ] %-32s d = %+.15f (closed form %+.15f, err %.1e; tol 1e-14), |grad| = %.15f\n", k.what, d,
                k.want, std::fabs(d - k.want), norm(g));
    EXPECT_NEAR(d, k.want, 1e-14) << k.what;
    EXPECT_NEAR(norm(g), 1.0, 1e-14) << k.what;
  }
}

}  // namespace
}  // namespace cgdem::geometry
