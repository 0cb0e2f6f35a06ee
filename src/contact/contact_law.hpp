// Linear spring-dashpot contact with Coulomb friction and tangential history, scaled for
// coarse-grained parcels (paper eqs. 6-7, 16-17; physics.md section 1).
//
//   normal      F_n = l^3 ( k delta - eta v_n ) n                         eq. (6)
//   tangential  F_t* = l^3 ( -k xi - eta v_t ),   xi += v_t dt (history)  eq. (7)
//               |F_t*| <= mu |F_n| : F_t = F_t*  (sticking)
//               otherwise          : F_t = mu |F_n| F_t*/|F_t*|  (sliding; l^3 applied once,
//                                    through F_n), xi reset to match F_t
//   damping     eta = 2 zeta sqrt(m_eff k),  zeta = -ln e / sqrt(pi^2 + ln^2 e),
//               m_eff of the ORIGINAL pair (m_O/2 particle-particle, m_O particle-wall),
//               so that e and the contact time are the same for every l.
//
// n is the unit normal pointing from the partner (particle or wall) to this particle,
// delta > 0 the overlap, v_rel the velocity of this particle's contact point relative to
// the partner's. The returned force acts on this particle. The law is written so that
// evaluating it from the partner's side (n -> -n, v_rel -> -v_rel, xi -> -xi) gives
// exactly the negated force: Newton's third law holds to the last bit.
#pragma once
#include <cmath>
#include <numbers>

#include "core/vec3.hpp"

namespace cgdem::contact {

// Parameters of one kind of contact (a species pair, or a species and the walls).
struct Params {
  double k = 0;    // spring stiffness of an original contact [N/m]
  double eta = 0;  // damping coefficient of an original contact [kg/s]
  double mu = 0;   // Coulomb friction coefficient
  double l3 = 1;   // number of simultaneous original contacts (l^3)
};

inline double damping_ratio(double e) {
  double le = std::log(e);
  return -le / std::sqrt(std::numbers::pi * std::numbers::pi + le * le);
}
inline double damping_coefficient(double e, double m_eff, double k) {
  return 2.0 * damping_ratio(e) * std::sqrt(m_eff * k);
}
// Closed forms of an isolated linear spring-dashpot collision (references.md).
inline double contact_time(double e, double m_eff, double k) {
  double z = damping_ratio(e);
  return std::numbers::pi * std::sqrt(m_eff / k) / std::sqrt(1.0 - z * z);
}

// Energy bookkeeping of one contact over one step.
struct Work {
  double damping_n = 0;  // energy dissipated by the normal dashpot [J]
  double friction = 0;   // energy dissipated tangentially (dashpot and sliding) [J]
};

// Force on this particle; updates the tangential history xi. Tangential force is also
// returned separately (for the torque). `work` receives the dissipated energy in dt.
inline Vec3 force(const Params& p, const Vec3& n, double delta, const Vec3& v_rel, Vec3& xi, double dt,
                  Vec3& f_t, Work& work) {
  const double vn = dot(v_rel, n);
  const Vec3 vt = v_rel - vn * n;
  const double fn_mag = p.l3 * (p.k * delta - p.eta * vn);  // eq. (6), signed (+ = repulsive)
  const Vec3 f_n = fn_mag * n;

  // History: keep xi in the current tangent plane with its length, then integrate.
  const double xi_len2 = norm2(xi);
  Vec3 s = xi - dot(xi, n) * n;
  if (xi_len2 > 0) {
    const double s_len2 = norm2(s);
    if (s_len2 > 0) s *= std::sqrt(xi_len2 / s_len2);
  }
  const double e_spring_old = 0.5 * p.l3 * p.k * norm2(s);
  s += dt * vt;

  f_t = -p.l3 * (p.k * s + p.eta * vt);  // eq. (7), sticking branch
  const double ft2 = norm2(f_t), limit = p.mu * std::fabs(fn_mag);
  if (ft2 > limit * limit) {  // sliding: scale onto the Coulomb cone, reset the spring
    f_t *= limit / std::sqrt(ft2);
    s = -(f_t / p.l3 + p.eta * vt) / p.k;
  }
  xi = s;
  const double e_spring_new = 0.5 * p.l3 * p.k * norm2(s);
  work.damping_n = p.l3 * p.eta * vn * vn * dt;
  // Work done on the contact by the tangential motion, minus what the spring stored.
  work.friction = -dot(f_t, vt) * dt - (e_spring_new - e_spring_old);
  return f_n + f_t;
}

}  // namespace cgdem::contact
