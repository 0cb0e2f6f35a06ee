// Set-up of the Hertz-Mindlin law: effective moduli, the damping factor that gives the
// case's restitution, the contact time for the time-step check, the [contact] reader.
#include "contact/hertz_mindlin.hpp"

#include <fmt/format.h>

#include <numbers>

#include "core/config.hpp"
#include "core/error.hpp"

namespace cgdem::contact {

namespace {

// Effective moduli of a contact between materials a and b (Hertz; Mindlin's no-slip
// tangential stiffness): 1/E* = sum (1 - nu^2)/E, 1/G* = sum (2 - nu)/G, G = E / (2 (1 + nu)).
double effective_young(double ea, double na, double eb, double nb) {
  return 1.0 / ((1 - na * na) / ea + (1 - nb * nb) / eb);
}
double effective_shear(double ea, double na, double eb, double nb) {
  const double ga = ea / (2 * (1 + na)), gb = eb / (2 * (1 + nb));
  return 1.0 / ((2 - na) / ga + (2 - nb) / gb);
}

// E*, G* of an original contact: two particles, or a particle and a wall.
void moduli(const HertzMindlinMaterial& m, bool wall, double& e_star, double& g_star) {
  const double eb = wall ? m.wall_youngs_modulus : m.youngs_modulus;
  const double nb = wall ? m.wall_poisson_ratio : m.poisson_ratio;
  e_star = effective_young(m.youngs_modulus, m.poisson_ratio, eb, nb);
  g_star = effective_shear(m.youngs_modulus, m.poisson_ratio, eb, nb);
}

// One RK4 step of the dimensionless collision x'' = -x^{3/2} - c x^{1/4} x' (c = sqrt(3/2) g).
void rk4_step(double c, double h, double& x, double& y) {
  auto acc = [c](double x, double y) {
    const double xp = x > 0 ? x : 0;
    return -xp * std::sqrt(xp) - c * std::sqrt(std::sqrt(xp)) * y;
  };
  const double k1x = y, k1y = acc(x, y);
  const double k2x = y + 0.5 * h * k1y, k2y = acc(x + 0.5 * h * k1x, y + 0.5 * h * k1y);
  const double k3x = y + 0.5 * h * k2y, k3y = acc(x + 0.5 * h * k2x, y + 0.5 * h * k2y);
  const double k4x = y + h * k3y, k4y = acc(x + h * k3x, y + h * k3y);
  x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
  y += h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y);
}

}  // namespace

HertzCollision hertz_collision(double g) {
  // Dimensionless time: the undamped collision lasts 3.218. Steps of 1e-4 give e to 5e-7
  // (against steps of 1e-5: 0.7073518 / 0.7073513 at g = 0.2); the overlap's root within
  // the last step is interpolated linearly (the acceleration vanishes there).
  const double c = std::sqrt(1.5) * g, h = 1e-4;
  double x = 0, y = 1;
  for (long k = 0; k < 2'000'000; ++k) {
    const double x0 = x, y0 = y;
    rk4_step(c, h, x, y);
    if (x <= 0 && k > 0) {
      const double f = x0 / (x0 - x);
      return {-(y0 + f * (y - y0)), (static_cast<double>(k) + f) * h};
    }
  }
  return {0, INFINITY};  // not separated after 60 elastic contact times: the pair sticks
}

double hertz_restitution(double g) { return hertz_collision(g).restitution; }

double hertz_damping_factor(double e) {
  if (!(e >= kMinHertzRestitution && e <= 1))
    throw Error(fmt::format("Hertz-Mindlin: restitution {} is outside [{}, 1]", e, kMinHertzRestitution));
  if (e == 1) return 0;
  // e(g) falls from 1 at g = 0 to 0.0108 at g = 1.5 and 0 near g = 1.7 (the pair sticks).
  double lo = 0, hi = 2;
  for (int it = 0; it < 100 && hi - lo > 1e-13; ++it) {
    const double mid = 0.5 * (lo + hi);
    (hertz_restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double hertz_contact_time(double m, double kn, double v) {
  // t_c = 2 int_0^dmax d(delta) / sqrt(v^2 - (4/5)(kn/m) delta^{5/2})
  //     = 2 (dmax / v) int_0^1 dx / sqrt(1 - x^{5/2}) = 2 (dmax / v) (2/5) B(2/5, 1/2).
  const double dmax = std::pow(5 * m * v * v / (4 * kn), 0.4);
  const double integral = 0.4 * std::tgamma(0.4) * std::sqrt(std::numbers::pi) / std::tgamma(0.9);
  return 2 * integral * dmax / v;
}

HertzMindlin::Params HertzMindlin::params(const Material& m, const OriginalPair& o) {
  double e_star, g_star;
  moduli(m, o.wall, e_star, g_star);
  const double g = hertz_damping_factor(o.wall ? m.wall_restitution : m.restitution);
  Params p;
  p.kn = 4.0 / 3.0 * e_star * std::sqrt(o.r_eff);
  p.kt = 8 * g_star * std::sqrt(o.r_eff);
  p.cn = g * std::sqrt(1.5 * o.m_eff * p.kn);
  p.ct = g * std::sqrt(o.m_eff * p.kt);
  p.mu = o.wall ? m.wall_friction : m.friction;
  p.l3 = o.l3;
  return p;
}

double HertzMindlin::collision_time(const Material& m, const OriginalPair& o) {
  double e_star, g_star;
  moduli(m, o.wall, e_star, g_star);
  return hertz_contact_time(o.m_eff, 4.0 / 3.0 * e_star * std::sqrt(o.r_eff), m.max_impact_speed);
}

HertzMindlin::Material HertzMindlin::read(const Section& s) {
  constexpr double kMaxModulus = 1e13;  // Pa (diamond: 1.2e12)
  constexpr double kMaxFriction = 5.0;
  const Range poisson{-1.0, 0.5, true, false};  // (-1, 0.5]
  const Range restitution = Range::closed(kMinHertzRestitution, 1);
  Material m;
  m.youngs_modulus = s.number("youngs_modulus", Range::open_closed(0, kMaxModulus));
  m.poisson_ratio = s.number("poisson_ratio", poisson);
  m.restitution = s.number("restitution", restitution);
  m.friction = s.number("friction", Range::closed(0, kMaxFriction));
  m.wall_youngs_modulus = s.number_or("wall_youngs_modulus", m.youngs_modulus, Range::open_closed(0, kMaxModulus));
  m.wall_poisson_ratio = s.number_or("wall_poisson_ratio", m.poisson_ratio, poisson);
  m.wall_restitution = s.number_or("wall_restitution", m.restitution, restitution);
  m.wall_friction = s.number_or("wall_friction", m.friction, Range::closed(0, kMaxFriction));
  m.max_impact_speed = s.number_or("max_impact_speed", 1.0, Range::open_closed(0, 1e3));
  return m;
}

}  // namespace cgdem::contact
