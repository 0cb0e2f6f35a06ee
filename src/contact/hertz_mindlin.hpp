// Hertz-Mindlin contact with Coulomb friction and tangential history, scaled for
// coarse-grained parcels the way the paper scales its linear law ([contact] law =
// "hertz-mindlin"; docs/contact_laws.md gives the derivation and the choices).
//
// One ORIGINAL contact of reduced radius R*, reduced mass m*, effective moduli E*, G*:
//   normal      F_n = (4/3) E* sqrt(R*) delta^{3/2} - eta_n v_n            (Hertz)
//   tangential  F_t* = -k_t xi - eta_t v_t,  k_t = 8 G* sqrt(R* delta)      (Mindlin, no slip)
//               |F_t*| <= mu |F_n| : sticking; otherwise F_t on the Coulomb cone and xi
//               reset to match, as in the linear law
//   damping     eta = g sqrt(m* S), S = dF/d(delta) the tangent stiffness of the spring
//               (S_n = 2 E* sqrt(R* delta), S_t = k_t), g set so that a head-on collision
//               rebounds with the restitution e of the case (hertz_damping_factor).
// A parcel contact stands for l^3 such contacts at the parcel's overlap and relative
// velocity (paper eq. 6 read for Hertz): every force above is multiplied by l^3, the
// friction limit through F_n only. Mass and force then scale alike, so the overlap, the
// contact time and the restitution of a parcel collision are those of an original pair
// at the same impact speed, for every l.
//
// With p.kn = (4/3) E* sqrt(R*), p.kt = 8 G* sqrt(R*), p.cn = g sqrt(3/2 m* p.kn),
// p.ct = g sqrt(m* p.kt):  F_n = l^3 (kn delta^{3/2} - cn delta^{1/4} v_n),
// k_t = kt delta^{1/2}, eta_t = ct delta^{1/4}.
//
// Energy bookkeeping as in the linear law (linear_law.hpp), in a form that needs no
// stiffness of the last step: each step books 1/2 dt (F_d + F_d,prev) v_n for the normal
// dashpot (this force's first half kick and the last force's second), and for the
// tangential force its work minus the change of the spring energy 1/2 l^3 k_t |xi|^2,
// with the energy left at the last step carried in the history.
#pragma once
#include <cmath>

#include "contact/history.hpp"

namespace cgdem {

class Section;

// What a case gives for the Hertz-Mindlin law ([contact] keys of the same names; a case
// must give youngs_modulus and poisson_ratio). The defaults here are a powder as soft as
// the paper's k = 50 N/m spring: for d_O = 125 um a collision at 0.1 m/s lasts 1.26e-5 s
// at e = 0.9 (the linear law: 1.23e-5 s).
struct HertzMindlinMaterial {
  double youngs_modulus = 2e7;  // E of the particles' material [Pa]
  double poisson_ratio = 0.3;   // nu
  double restitution = 0.9;     // e, particle-particle
  double friction = 0.3;        // mu, particle-particle
  double wall_youngs_modulus = 2e7;  // E of the walls [Pa]
  double wall_poisson_ratio = 0.3;
  double wall_restitution = 0.9;
  double wall_friction = 0.3;
  // The fastest head-on impact the time step must resolve [m/s]: a Hertz contact is the
  // shorter the faster the impact (t_c ~ v^-1/5), so the time-step check needs a speed.
  double max_impact_speed = 1.0;
};

namespace contact {

// The smallest restitution the Hertzian dashpot is used for: below, g nears the value
// (about 1.7) at which a pair no longer separates (at e = 0.01 the contact already lasts
// 2.6 times the elastic contact time, and longer without bound as e falls).
inline constexpr double kMinHertzRestitution = 0.01;
// The damping factor g of the law above for which a head-on collision rebounds with
// restitution e (kMinHertzRestitution <= e <= 1; g = 0 for e = 1): the dimensionless collision
// x'' = -x^{3/2} - sqrt(3/2) g x^{1/4} x', x(0) = 0, x'(0) = 1, rebounds with -x' = e, whatever
// the material, size and impact speed. Solved once per restitution (hertz_mindlin.cpp).
double hertz_damping_factor(double e);
// That dimensionless collision for damping factor g: its restitution (the inverse of
// hertz_damping_factor) and its duration in units of D / v, D = (m v^2 / kn)^{2/5}
// (3.218 undamped).
struct HertzCollision {
  double restitution, duration;
};
HertzCollision hertz_collision(double g);
double hertz_restitution(double g);
// Duration of an undamped Hertz collision of reduced mass m at impact speed v with
// F = kn delta^{3/2}: 2.9432 delta_max / v, delta_max = (5 m v^2 / (4 kn))^{2/5}.
double hertz_contact_time(double m, double kn, double v);

struct HertzMindlin {
  using Material = HertzMindlinMaterial;
  struct Params {
    double kn = 0;  // (4/3) E* sqrt(R*) [N/m^1.5]
    double kt = 0;  // 8 G* sqrt(R*) [N/m^1.5]
    double cn = 0;  // normal dashpot eta_n / delta^{1/4} [kg/(s m^0.25)]
    double ct = 0;  // tangential dashpot eta_t / delta^{1/4}
    double mu = 0;  // Coulomb friction coefficient
    double l3 = 1;  // number of simultaneous original contacts (l^3)
  };
  struct History {
    Vec3 xi;            // tangential spring displacement [m]
    Vec3 ft;            // last tangential force on this particle [N]
    double fd = 0;      // last normal dashpot force l^3 eta_n v_n [N]
    double carried = 0; // spring energy at the last step + 1/2 dt (F_t . v_t) of the last step [J]
  };
  static History unpack(const contact::History& r) { return {r.xi, r.ft, r.s1, r.s2}; }
  static contact::History pack(const History& h) { return {h.xi, h.ft, h.fd, h.carried}; }

  static Params params(const Material& m, const OriginalPair& o);
  // The undamped contact time at max_impact_speed (damping only lengthens a collision).
  static double collision_time(const Material& m, const OriginalPair& o);
  static double elastic_energy(const Params& p, double delta, const History& h) {
    const double sd = std::sqrt(delta);
    return p.l3 * (0.4 * p.kn * delta * delta * sd + 0.5 * p.kt * sd * norm2(h.xi));
  }

  // Force on this particle, as LinearSpringDashpot::force (same conventions, branch-free).
  static Vec3 force(const Params& p, const Vec3& n, double delta, const Vec3& v_rel, History& h, double dt,
                    Vec3& f_t, Work& work) {
    const double vn = dot(v_rel, n);
    const Vec3 vt = v_rel - vn * n;
    const double sd = cgdem_sqrt(select(delta > 0, delta, 0.0));  // delta^{1/2}
    const double qd = cgdem_sqrt(sd);                              // delta^{1/4}
    const double fd = p.l3 * (p.cn * qd) * vn;
    const double fn_mag = p.l3 * p.kn * delta * sd - fd;  // Hertz, signed (+ = repulsive)
    const Vec3 f_n = fn_mag * n;
    const double kt = p.kt * sd, eta_t = p.ct * qd;

    // History: keep xi in the current tangent plane with its length, then integrate.
    const Vec3& xi = h.xi;
    const double xi_len2 = norm2(xi);
    const double xn = dot(xi, n);
    Vec3 s = xi - xn * n;
    const double s_len2 = xi_len2 - xn * xn;
    s *= select(s_len2 > 0, cgdem_sqrt(xi_len2 / s_len2), 1.0);
    s += dt * vt;

    f_t = -p.l3 * (kt * s + eta_t * vt);  // Mindlin, sticking
    const double ft2 = norm2(f_t), limit = p.mu * std::fabs(fn_mag);
    const bool sliding = ft2 > limit * limit;
    f_t *= select(sliding, limit / cgdem_sqrt(ft2), 1.0);
    s = select(sliding & (kt > 0), -(f_t / p.l3 + eta_t * vt) / kt, s);
    const double e_spring = 0.5 * p.l3 * kt * norm2(s);
    const double ftvt = dot(f_t, vt);
    work.damping_n = 0.5 * dt * (fd + h.fd) * vn;
    work.friction = -ftvt * dt - e_spring + h.carried - 0.5 * dt * dot(h.ft, vt);
    h = {s, f_t, fd, e_spring + 0.5 * dt * ftvt};
    return f_n + f_t;
  }

  // The contact has ended: the last forces' second halves and the spring's energy.
  static void finish(const Params&, const Vec3& n, const Vec3& v_rel, History& h, double dt, Work& work) {
    const double vn = dot(v_rel, n);
    const Vec3 vt = v_rel - vn * n;
    work.damping_n = 0.5 * dt * h.fd * vn;
    work.friction = h.carried - 0.5 * dt * dot(h.ft, vt);
    h = History{};
  }

  // The registry's parameter reader: [contact] of a case file.
  static Material read(const Section& s);
};

}  // namespace contact
}  // namespace cgdem
