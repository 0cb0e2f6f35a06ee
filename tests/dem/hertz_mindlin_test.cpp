// The Hertz-Mindlin law (contact/hertz_mindlin.hpp, docs/contact_laws.md) against closed
// forms. The reference values are computed here from the textbook formulas, not from the
// library's own helpers:
//   E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2),  G* = 1 / ((2 - nu1)/G1 + (2 - nu2)/G2)
//   Hertz, undamped head-on collision at relative speed v, reduced mass m*, radius R*:
//     delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5},
//     t_c = 2 (2/5) B(2/5, 1/2) delta_max / v = 2.9432 delta_max / v,  e = 1
//   Mindlin no slip: k_t = 8 G* sqrt(R* delta); k_t / (dF_n/d delta) = 4 G* / E*
//   (= 2 (1 - nu) / (2 - nu) for one material).
// With damping, the restitution of the case is reached for every impact speed and every
// l (the dashpot's delta^{1/4} makes it speed-independent; l^3 scales mass and force alike).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact/laws.hpp"
#include "dem_test_util.hpp"
#include "geometry/shape.hpp"

namespace cgdem {
namespace {

constexpr double kE = 2e7, kNu = 0.3;  // a soft powder: t_c ~ 1e-5 s at 0.1 m/s for d_O = 125 um

HertzMindlinMaterial material(double e) {
  HertzMindlinMaterial m;
  m.youngs_modulus = m.wall_youngs_modulus = kE;
  m.poisson_ratio = m.wall_poisson_ratio = kNu;
  m.restitution = m.wall_restitution = e;
  m.friction = m.wall_friction = 0.3;
  return m;
}

double e_star(double e1, double n1, double e2, double n2) { return 1 / ((1 - n1 * n1) / e1 + (1 - n2 * n2) / e2); }

// Hertz's undamped collision (header comment).
double max_overlap(double m, double es, double r, double v) {
  return std::pow(15 * m * v * v / (16 * es * std::sqrt(r)), 0.4);
}
double contact_time(double m, double es, double r, double v) {
  const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);  // B(2/5, 1/2)
  return 2 * 0.4 * beta * max_overlap(m, es, r, v) / v;
}

struct Outcome {
  double restitution, contact_time, max_overlap;
};

// Tracks one collision: overlap(dem) > 0 while in contact; returns its duration (the sign
// changes interpolated linearly), largest overlap and the solver, stepped past the contact.
template <class Overlap>
void track(DemSolver& dem, Overlap overlap_of, double t_max, double prev, Outcome& o) {
  double t_in = -1, t_out = -1;
  o.max_overlap = 0;
  while (t_out < 0 && dem.time() < t_max) {
    dem.step();
    const double overlap = overlap_of(dem), dt = dem.params().dt;
    if (prev <= 0 && overlap > 0) t_in = dem.time() - dt * overlap / (overlap - prev);
    if (prev > 0 && overlap <= 0) t_out = dem.time() - dt * overlap / (overlap - prev);
    o.max_overlap = std::max(o.max_overlap, overlap);
    prev = overlap;
  }
  o.contact_time = t_out - t_in;
}

// Two parcels head-on along x at relative speed `speed`; dt = t_c / 400.
Outcome pair_collision(const HertzMindlinMaterial& m, double l, double speed) {
  const Species s = test::powder(l);
  const double tc = contact_time(0.5 * s.original_mass(), e_star(kE, kNu, kE, kNu), 0.25 * s.d_original, speed);
  DemSolver dem({s}, m, test::no_gravity(tc / 400), geometry::Scene{});
  const double r = 0.5 * s.diameter(), gap = 1e-3 * r;
  dem.particles().add(0, 0, s, {-r - gap / 2, 0, 0}, {0.5 * speed, 0, 0});
  dem.particles().add(1, 0, s, {r + gap / 2, 0, 0}, {-0.5 * speed, 0, 0});
  auto overlap = [r](const DemSolver& d) {
    const auto& p = d.particles();
    const int a = p.id[0] == 0 ? 0 : 1, b = 1 - a;
    return 2 * r - (p.x[b].x - p.x[a].x);
  };
  Outcome o{};
  track(dem, overlap, 20 * tc + gap / speed, -gap, o);
  const auto& p = dem.particles();
  const int a = p.id[0] == 0 ? 0 : 1, b = 1 - a;
  o.restitution = (p.v[b].x - p.v[a].x) / speed;
  return o;
}

TEST(HertzMindlin, UndampedPairCollisionMatchesHertzForEveryRatio) {
  const HertzMindlinMaterial m = material(1.0);
  const Species s1 = test::powder(1);
  const double m_eff = 0.5 * s1.original_mass(), r_eff = 0.25 * s1.d_original, es = e_star(kE, kNu, kE, kNu);
  double worst_e = 0, worst_t = 0, worst_d = 0;
  for (double l : {1.0, 2.0, 3.0}) {
    for (double v : {0.05, 0.5, 2.0}) {
      const Outcome o = pair_collision(m, l, v);
      const double tc = contact_time(m_eff, es, r_eff, v), dm = max_overlap(m_eff, es, r_eff, v);
      const double err_e = std::fabs(o.restitution - 1), err_t = test::rel_err(o.contact_time, tc),
                   err_d = test::rel_err(o.max_overlap, dm);
      std::printf("[ hertz pair e=1 ] l=%.0f v=%.2f: e=%.7f (err %.1e)  t_c=%.5e s (Hertz %.5e, err %.1e)  "
                  "delta_max=%.5e m (Hertz %.5e, err %.1e)\n",
                  l, v, o.restitution, err_e, o.contact_time, tc, err_t, o.max_overlap, dm, err_d);
      worst_e = std::max(worst_e, err_e), worst_t = std::max(worst_t, err_t), worst_d = std::max(worst_d, err_d);
    }
  }
  std::printf("[ hertz pair e=1 ] worst errors: e %.1e, t_c %.1e, delta_max %.1e (tol 1e-4 each)\n", worst_e,
              worst_t, worst_d);
  EXPECT_LT(worst_e, 1e-4);
  EXPECT_LT(worst_t, 1e-4);
  EXPECT_LT(worst_d, 1e-4);
}

TEST(HertzMindlin, DampedPairCollisionHasTheCaseRestitutionAtEverySpeedAndRatio) {
  const Species s1 = test::powder(1);
  const double m_eff = 0.5 * s1.original_mass(), r_eff = 0.25 * s1.d_original, es = e_star(kE, kNu, kE, kNu);
  const double kn = 4.0 / 3.0 * es * std::sqrt(r_eff);
  for (double e : {0.5, 0.9}) {
    // The dimensionless collision for the calibrated damping: duration in units of D / v.
    const contact::HertzCollision ref = contact::hertz_collision(contact::hertz_damping_factor(e));
    double worst_e = 0, worst_t = 0;
    for (double l : {1.0, 2.0, 3.0}) {
      for (double v : {0.05, 0.5, 2.0}) {
        const Outcome o = pair_collision(material(e), l, v);
        const double tc = ref.duration * std::pow(m_eff * v * v / kn, 0.4) / v;
        const double err_e = test::rel_err(o.restitution, e), err_t = test::rel_err(o.contact_time, tc);
        std::printf("[ hertz pair e=%.1f ] l=%.0f v=%.2f: e=%.6f (err %.1e)  t_c=%.5e s (ref %.5e, %.3f x the "
                    "undamped Hertz time, err %.1e)\n",
                    e, l, v, o.restitution, err_e, o.contact_time, tc, tc / contact_time(m_eff, es, r_eff, v), err_t);
        worst_e = std::max(worst_e, err_e), worst_t = std::max(worst_t, err_t);
      }
    }
    std::printf("[ hertz pair e=%.1f ] worst errors: e %.1e, t_c %.1e (tol 1e-3 each)\n", e, worst_e, worst_t);
    EXPECT_LT(worst_e, 1e-3);
    EXPECT_LT(worst_t, 1e-3);
  }
}

// Parcel falling (no gravity) onto a flat wall of another material: E*, R* = r_O, m* = m_O.
TEST(HertzMindlin, WallCollisionUsesBothMaterials) {
  const double ew = 1e8, nw = 0.2;
  for (double e : {1.0, 0.7}) {
    HertzMindlinMaterial m = material(e);
    m.wall_youngs_modulus = ew, m.wall_poisson_ratio = nw;
    for (double l : {1.0, 3.0}) {
      const Species s = test::powder(l);
      const double v = 0.3, mo = s.original_mass(), ro = 0.5 * s.d_original, es = e_star(kE, kNu, ew, nw);
      const double tc0 = contact_time(mo, es, ro, v);
      const contact::HertzCollision ref = contact::hertz_collision(contact::hertz_damping_factor(e));
      const double tc = ref.duration * std::pow(mo * v * v / (4.0 / 3.0 * es * std::sqrt(ro)), 0.4) / v;
      geometry::Scene scene;
      const int b = scene.add_body("floor", geometry::Motion{});
      scene.add_part(b, "plane", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
      DemSolver dem({s}, m, test::no_gravity(tc0 / 400), scene);
      const double r = 0.5 * s.diameter();
      dem.particles().add(0, 0, s, {0, 0, r * (1 + 1e-3)}, {0, 0, -v});
      Outcome o{};
      track(dem, [r](const DemSolver& d) { return r - d.particles().x[0].z; }, 1.0, -1e-3 * r, o);
      o.restitution = dem.particles().v[0].z / v;
      const double err_e = test::rel_err(o.restitution, e), err_t = test::rel_err(o.contact_time, tc);
      std::printf("[ hertz wall ] e=%.1f l=%.0f: e=%.6f (err %.1e)  t_c=%.5e s (ref %.5e, err %.1e; tol 1e-3)\n", e,
                  l, o.restitution, err_e, o.contact_time, tc, err_t);
      EXPECT_LT(err_e, 1e-3);
      EXPECT_LT(err_t, 1e-3);
    }
  }
}

// The force function itself: Hertz's static force and Mindlin's no-slip stiffness, to rounding.
TEST(HertzMindlin, StaticForceAndTangentialStiffnessAreHertzAndMindlin) {
  using Law = contact::HertzMindlin;
  const Species s = test::powder(3);
  const contact::OriginalPair o = contact::original_pair(s, s);
  const Law::Params p = Law::params(material(1.0), o);  // undamped: the springs alone
  const double es = e_star(kE, kNu, kE, kNu), g = kE / (2 * (1 + kNu)), gs = 1 / (2 * (2 - kNu) / g);
  const double r = 0.25 * s.d_original, delta = 2e-7, dt = 1e-7, vt = 1e-3;
  const Vec3 n{0, 0, 1};
  Law::History h;
  Vec3 f_t;
  contact::Work w;
  const Vec3 f = Law::force(p, n, delta, {vt, 0, 0}, h, dt, f_t, w);
  const double fn = 27 * 4.0 / 3.0 * es * std::sqrt(r) * std::pow(delta, 1.5);
  const double kt = 8 * gs * std::sqrt(r * delta), ft = -27 * kt * vt * dt;  // xi = v_t dt after one step
  const double kn_tangent = 2 * es * std::sqrt(r * delta);                    // dF_n/d delta of one contact
  const double err_n = test::rel_err(f.z, fn), err_t = test::rel_err(f_t.x, ft);
  const double ratio = kt / kn_tangent, ratio_ref = 2 * (1 - kNu) / (2 - kNu);
  std::printf("[ hertz static ] l=3: F_n=%.9e N (Hertz %.9e, err %.1e)  F_t=%.9e N (Mindlin %.9e, err %.1e)  "
              "k_t/k_n=%.6f (2(1-nu)/(2-nu) = %.6f, err %.1e); tol 1e-13\n",
              f.z, fn, err_n, f_t.x, ft, err_t, ratio, ratio_ref, std::fabs(ratio - ratio_ref));
  EXPECT_LT(err_n, 1e-13);
  EXPECT_LT(err_t, 1e-13);
  EXPECT_NEAR(ratio, ratio_ref, 1e-13);
  EXPECT_EQ(h.xi.x, vt * dt);
  // Sliding: a large tangential step puts F_t on the Coulomb cone, the spring reset to match.
  Law::History hs;
  Law::force(p, n, delta, {1e3, 0, 0}, hs, dt, f_t, w);
  const double cone = test::rel_err(-f_t.x, 0.3 * fn), spring = test::rel_err(f_t.x, -27 * kt * hs.xi.x);
  std::printf("[ hertz sliding ] |F_t| / (mu F_n) - 1 = %.1e, F_t against -l^3 k_t xi: %.1e (tol 1e-13)\n", cone,
              spring);
  EXPECT_LT(cone, 1e-13);
  EXPECT_LT(spring, 1e-13);
}

// The damping factor's calibration: e(g) inverts it, g(1) = 0, and the dimensionless
// collision is resolved (halving its own step changes nothing at 1e-6).
TEST(HertzMindlin, DampingFactorReproducesRestitution) {
  EXPECT_EQ(contact::hertz_damping_factor(1.0), 0.0);
  const contact::HertzCollision undamped = contact::hertz_collision(0);
  const double tau = 2 * 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) * std::pow(1.25, 0.4);
  std::printf("[ hertz calibration ] g=0: e=%.12f, duration %.9f (Hertz %.9f)\n", undamped.restitution,
              undamped.duration, tau);
  EXPECT_NEAR(undamped.restitution, 1.0, 1e-9);
  EXPECT_NEAR(undamped.duration, tau, 1e-6);
  for (double e : {0.01, 0.1, 0.5, 0.9, 0.99}) {
    const double g = contact::hertz_damping_factor(e), back = contact::hertz_restitution(g);
    std::printf("[ hertz calibration ] e=%.2f: g=%.9f, e(g)=%.12f (err %.1e, tol 1e-10)\n", e, g, back,
                std::fabs(back - e));
    EXPECT_NEAR(back, e, 1e-10);
  }
}

// The energy budget closes as for the linear law (budget_test.cpp, the same three spinning
// parcels bouncing for 30 ms with damping and friction).
TEST(HertzMindlin, EnergyBudgetClosesAndShrinksWithDt) {
  const double e1 = test::closure_error(1e-6, material(0.7)), e4 = test::closure_error(0.25e-6, material(0.7));
  std::printf("[ hertz budget ] largest closure error / energy released: dt=1e-6 %.2e, 2.5e-7 %.2e "
              "(tol: 1e-2 at 1e-6; dt/4 at least 2x smaller: %.1fx)\n",
              e1, e4, e1 / e4);
  EXPECT_LT(e1, 1e-2);
  EXPECT_GT(e1 / e4, 2.0);
}

}  // namespace
}  // namespace cgdem
