// A sphere launched without spin on a frictional floor slides, then rolls:
// rolling starts at t* = 2 v0 / (7 mu g) with v = 5/7 v0 (docs/references.md, Sliding). The contact
// history is carried across many neighbour-list rebuilds on the way (the sphere travels
// far more than the skin).
#include <gtest/gtest.h>

#include "dem_test_util.hpp"
#include "geometry/shape.hpp"

namespace cgdem {
namespace {

TEST(Sliding, RollingStartsAtClosedFormTimeAndSpeed) {
  for (double l : {1.0, 3.0}) {
    const double v0 = 0.1, mu = 0.3, g = 9.81;
    Species s = test::powder(l);
    MaterialParams m;
    m.wall_friction = mu;
    m.wall_restitution = 0.5;  // damps the initial normal oscillation quickly
    geometry::Scene scene;
    int b = scene.add_body("floor", geometry::Motion{});
    scene.add_part(b, "plane", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
    DemParams p;
    p.dt = 2e-7;
    p.gravity = {0, 0, -g};
    p.domain = {{-1, -1, -1}, {1, 1, 1}};
    DemSolver dem({s}, m, p, scene);
    const double r = 0.5 * s.diameter();
    const double sag = s.mass() * g / (s.l3() * m.stiffness);  // static overlap
    dem.particles().add(0, 0, s, {0, 0, r - sag}, {v0, 0, 0});

    const double t_star = 2 * v0 / (7 * mu * g);
    double t_roll = -1, v_roll = 0;
    double prev_slip = v0;
    while (dem.time() < 2 * t_star) {
      dem.step();
      const auto& q = dem.particles();
      // Slip velocity of the contact point: v + w x (-r e_z), x-component.
      double slip = q.v[0].x - r * q.omega[0].y;
      if (t_roll < 0 && slip <= 1e-4 * v0) {
        // interpolate the zero crossing of the slip velocity
        double f = prev_slip / (prev_slip - slip);
        t_roll = dem.time() - p.dt * (1 - f);
        v_roll = q.v[0].x;
      }
      prev_slip = slip;
    }
    const double err_t = test::rel_err(t_roll, t_star), err_v = test::rel_err(v_roll, 5.0 / 7.0 * v0);
    std::printf("[ sliding ] l=%.0f: t_roll=%.5e s (ref %.5e, err %.2e)  v=%.5f m/s (ref %.5f, err %.2e)  tol 1e-2, "
                "list builds %ld\n",
                l, t_roll, t_star, err_t, v_roll, 5.0 / 7.0 * v0, err_v, dem.neighbor_builds());
    EXPECT_LT(err_t, 1e-2);
    EXPECT_LT(err_v, 1e-2);
    EXPECT_GT(dem.neighbor_builds(), 5);  // history survived rebuilds
  }
}

}  // namespace
}  // namespace cgdem
