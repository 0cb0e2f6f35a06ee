// Binary normal collisions against the closed forms of the linear spring-dashpot
// (docs/references.md, Collision): restitution e and contact time t_c = pi sqrt(m_eff/k)/sqrt(1-zeta^2),
// with m_eff of the ORIGINAL pair, the same for every coarse-grain ratio l (docs/model.md, section 1).
#include <gtest/gtest.h>

#include "dem_test_util.hpp"
#include "geometry/shape.hpp"

namespace cgdem {
namespace {

struct Outcome {
  double restitution, contact_time;
};

// Two parcels approaching head-on along x at relative speed `speed`.
Outcome pair_collision(double l, double speed, double e) {
  Species s = test::powder(l);
  MaterialParams m;
  m.restitution = e;
  m.friction = 0.3;
  const double m_eff = 0.5 * s.original_mass();
  const double tc = contact::contact_time(e, m_eff, m.stiffness);
  DemSolver dem({s}, m, test::no_gravity(tc / 400), geometry::Scene{});
  const double r = 0.5 * s.diameter(), gap = 0.2 * r;
  dem.particles().add(0, 0, s, {-r - gap / 2, 0, 0}, {0.5 * speed, 0, 0});
  dem.particles().add(1, 0, s, {r + gap / 2, 0, 0}, {-0.5 * speed, 0, 0});
  double t_in = -1, t_out = -1, prev = -gap;  // overlap = 2r - distance
  while (t_out < 0 && dem.time() < 10 * tc + gap / speed) {
    dem.step();
    const auto& p = dem.particles();
    int a = p.id[0] == 0 ? 0 : 1, b = 1 - a;
    double overlap = 2 * r - (p.x[b].x - p.x[a].x);
    double dt = dem.params().dt;
    // Linear interpolation of the instants the overlap changes sign.
    if (prev <= 0 && overlap > 0) t_in = dem.time() - dt * overlap / (overlap - prev);
    if (prev > 0 && overlap <= 0) t_out = dem.time() - dt * overlap / (overlap - prev);
    prev = overlap;
  }
  const auto& p = dem.particles();
  int a = p.id[0] == 0 ? 0 : 1, b = 1 - a;
  return {(p.v[b].x - p.v[a].x) / speed, t_out - t_in};
}

TEST(Collision, ParticleParticleMatchesClosedFormForEveryRatio) {
  for (double e : {0.5, 0.9}) {
    const double tc_ref = contact::contact_time(e, 0.5 * test::powder(1).original_mass(), 50.0);
    for (double l : {1.0, 2.0, 3.0}) {
      for (double speed : {0.05, 0.5, 2.0}) {
        Outcome o = pair_collision(l, speed, e);
        double err_e = test::rel_err(o.restitution, e), err_t = test::rel_err(o.contact_time, tc_ref);
        std::printf("[ pair ] e=%.2f l=%.0f v=%.2f: e_meas=%.5f (err %.2e)  t_c=%.4e s (ref %.4e, err %.2e)  tol 1e-2\n",
                    e, l, speed, o.restitution, err_e, o.contact_time, tc_ref, err_t);
        EXPECT_LT(err_e, 1e-2);
        EXPECT_LT(err_t, 1e-2);
      }
    }
  }
}

// Parcel against a wall moving at velocity U along its normal: the relative velocity
// reverses with factor e, v_out - U = -e (v_in - U); contact time with m_eff = m_O.
Outcome wall_collision(double l, double v_in, double u_wall, double e, double* v_out) {
  Species s = test::powder(l);
  MaterialParams m;
  m.wall_restitution = e;
  const double tc = contact::contact_time(e, s.original_mass(), m.stiffness);
  geometry::Scene scene;
  int b = scene.add_body("floor", geometry::Motion::constant({0, 0, u_wall}));
  scene.add_part(b, "plane", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  DemSolver dem({s}, m, test::no_gravity(tc / 400), scene);
  const double r = 0.5 * s.diameter();
  dem.particles().add(0, 0, s, {0, 0, 1.1 * r}, {0, 0, v_in});
  double t_in = -1, t_out = -1, prev = -0.1 * r;
  while (t_out < 0 && dem.time() < 1.0) {
    dem.step();
    double overlap = r - (dem.particles().x[0].z - u_wall * dem.time());
    double dt = dem.params().dt;
    if (prev <= 0 && overlap > 0) t_in = dem.time() - dt * overlap / (overlap - prev);
    if (prev > 0 && overlap <= 0) t_out = dem.time() - dt * overlap / (overlap - prev);
    prev = overlap;
  }
  *v_out = dem.particles().v[0].z;
  return {-(*v_out - u_wall) / (v_in - u_wall), t_out - t_in};
}

TEST(Collision, ParticleWallMatchesClosedFormForEveryRatio) {
  const double e = 0.9;
  const double tc_ref = contact::contact_time(e, test::powder(1).original_mass(), 50.0);
  for (double l : {1.0, 2.0, 3.0}) {
    for (double v : {-0.05, -0.5, -2.0}) {
      double v_out;
      Outcome o = wall_collision(l, v, 0.0, e, &v_out);
      double err_e = test::rel_err(o.restitution, e), err_t = test::rel_err(o.contact_time, tc_ref);
      std::printf("[ wall ] l=%.0f v=%.2f: e_meas=%.5f (err %.2e)  t_c=%.4e s (ref %.4e, err %.2e)  tol 1e-2\n", l,
                  v, o.restitution, err_e, o.contact_time, tc_ref, err_t);
      EXPECT_LT(err_e, 1e-2);
      EXPECT_LT(err_t, 1e-2);
    }
  }
}

TEST(Collision, MovingWallFollowsRelativeVelocityLaw) {
  const double e = 0.9;
  for (double l : {1.0, 3.0}) {
    for (double u : {0.1, 0.4}) {   // floor moving up into a particle that falls or rests
      double v_in = -0.2, v_out;
      wall_collision(l, v_in, u, e, &v_out);
      double want = u - e * (v_in - u);
      double err = std::fabs(v_out - want) / std::fabs(v_in - u);
      std::printf("[ moving wall ] l=%.0f U=%.2f v_in=%.2f: v_out=%.5f expected %.5f (err %.2e of |v_in-U|, tol 1e-2)\n",
                  l, u, v_in, v_out, want, err);
      EXPECT_LT(err, 1e-2);
    }
  }
}

TEST(Collision, RestitutionFromDampingRatioTable) {
  // docs/references.md table: zeta(e) and t_c sqrt(k/m_eff).
  const double e[] = {0.1, 0.3, 0.5, 0.7, 0.9, 0.95};
  const double zeta[] = {0.59116, 0.35786, 0.21545, 0.11281, 0.03352, 0.01632};
  const double tc[] = {3.89506, 3.36440, 3.21715, 3.16178, 3.14336, 3.14201};
  for (int i = 0; i < 6; ++i) {
    double z = contact::damping_ratio(e[i]), t = contact::contact_time(e[i], 1.0, 1.0);
    std::printf("[ table ] e=%.2f zeta=%.5f (ref %.5f)  t_c=%.5f (ref %.5f)\n", e[i], z, zeta[i], t, tc[i]);
    EXPECT_NEAR(z, zeta[i], 1e-5);
    EXPECT_NEAR(t, tc[i], 1e-5);
  }
}

}  // namespace
}  // namespace cgdem
