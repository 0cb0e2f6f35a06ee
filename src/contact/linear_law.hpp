// The paper's contact law: linear spring-dashpot with Coulomb friction and tangential
// history, scaled for coarse-grained parcels (paper eqs. 6-7, 16-17; docs/model.md,
// section 1). The default law of every case ([contact] law = "linear").
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
// evaluating it from the partner's side (n -> -n, v_rel -> -v_rel, history flipped) gives
// exactly the negated force: Newton's third law holds to the last bit.
#pragma once
#include <cmath>
#include <numbers>

#include "contact/history.hpp"

namespace cgdem {

class Section;

// What a case gives for the linear law ([contact] stiffness, restitution, friction,
// wall_restitution, wall_friction; the paper's Table 1 by default).
struct MaterialParams {
  double stiffness = 50;        // k [N/m]
  double restitution = 0.9;     // e, particle-particle
  double friction = 0.3;        // mu, particle-particle
  double wall_restitution = 0.9;
  double wall_friction = 0.3;
};

namespace contact {

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
// Closed forms of an isolated linear spring-dashpot collision (docs/references.md, Collision).
inline double contact_time(double e, double m_eff, double k) {
  double z = damping_ratio(e);
  return std::numbers::pi * std::sqrt(m_eff / k) / std::sqrt(1.0 - z * z);
}

struct LinearSpringDashpot {
  using Material = MaterialParams;
  using Params = contact::Params;

  // What a contact carries from one step to the next: the tangential spring, and the last
  // step's forces and velocities for the energy bookkeeping below.
  //
  // Energy bookkeeping. In velocity Verlet the force F computed at step n+1 (from the
  // half-step velocity v^{n+1/2}) acts through the two half kicks that take v^{n+1/2} to
  // v^{n+3/2}, so its work is F . (v^{n+1/2} + v^{n+3/2})/2 dt. Booking only F . v^{n+1/2} dt
  // leaves an error of first order in dt (for a dashpot, eta dt/(2 m) of what it
  // dissipates: 4 % at e = 0.5 here). So each evaluation books F . v^{n+1/2} dt for its own
  // force and the remainder F_prev . (v^{n+1/2} - v_prev) dt/2 for the previous step's
  // force; finish() books the remainder when the contact ends. The tangential dissipation
  // is its work minus the change of the spring's energy; the spring's own work then
  // telescopes to that change.
  struct History {
    Vec3 xi;          // tangential spring displacement [m]
    Vec3 ft;          // last tangential force on this particle [N]
    double vn = 0;    // last normal relative velocity [m/s] (the dashpot force was l^3 eta vn)
    double ftvt = 0;  // ft . v_t of the last step [W]
  };
  // The history serialization: slot for slot (history.hpp; xi and ft are the vectors).
  static History unpack(const contact::History& r) { return {r.xi, r.ft, r.s1, r.s2}; }
  static contact::History pack(const History& h) { return {h.xi, h.ft, h.vn, h.ftvt}; }

  // Parameters of the original contacts behind a parcel contact.
  static Params params(const Material& m, const OriginalPair& o) {
    const double e = o.wall ? m.wall_restitution : m.restitution;
    return {m.stiffness, damping_coefficient(e, o.m_eff, m.stiffness), o.wall ? m.wall_friction : m.friction, o.l3};
  }
  // Duration of a head-on collision (the same for every l and every impact speed).
  static double collision_time(const Material& m, const OriginalPair& o) {
    return contact_time(o.wall ? m.wall_restitution : m.restitution, o.m_eff, m.stiffness);
  }
  // Energy held by the springs of a contact of overlap delta.
  static double elastic_energy(const Params& p, double delta, const History& h) {
    return 0.5 * p.l3 * p.k * (delta * delta + norm2(h.xi));
  }

  // Force on this particle; updates the history h. Tangential force is also returned
  // separately (for the torque). `work` receives the dissipated energy in dt.
  // Written without branches (both cases computed, one selected) so that a loop over many
  // contacts vectorizes; a lane computes exactly what the branching code would.
  static Vec3 force(const Params& p, const Vec3& n, double delta, const Vec3& v_rel, History& h, double dt,
                    Vec3& f_t, Work& work) {
    const double vn = dot(v_rel, n);
    const Vec3 vt = v_rel - vn * n;
    const double fd = p.l3 * p.eta * vn;
    const double fn_mag = p.l3 * p.k * delta - fd;  // eq. (6), signed (+ = repulsive)
    const Vec3 f_n = fn_mag * n;

    // History: keep xi in the current tangent plane with its length, then integrate.
    const Vec3& xi = h.xi;
    const double xi_len2 = norm2(xi);
    const double xn = dot(xi, n);
    Vec3 s = xi - xn * n;
    const double s_len2 = xi_len2 - xn * xn;  // 0 when xi = 0
    s *= select(s_len2 > 0, cgdem_sqrt(xi_len2 / s_len2), 1.0);
    const double e_spring_old = 0.5 * p.l3 * p.k * xi_len2;  // the rotation keeps the length
    s += dt * vt;

    f_t = -p.l3 * (p.k * s + p.eta * vt);  // eq. (7), sticking branch
    const double ft2 = norm2(f_t), limit = p.mu * std::fabs(fn_mag);
    // Sliding: scale onto the Coulomb cone, reset the spring to match.
    const bool sliding = ft2 > limit * limit;
    f_t *= select(sliding, limit / cgdem_sqrt(ft2), 1.0);
    s = select(sliding, -(f_t / p.l3 + p.eta * vt) / p.k, s);
    const double e_spring_new = 0.5 * p.l3 * p.k * norm2(s);
    const double ftvt = dot(f_t, vt);
    // This step's force at v^{n+1/2}, plus the second half of the previous step's force.
    const double fd_old = p.l3 * p.eta * h.vn;  // the last step's dashpot force, as computed then
    work.damping_n = fd * vn * dt + 0.5 * dt * fd_old * (vn - h.vn);
    work.friction = -ftvt * dt - (e_spring_new - e_spring_old) - 0.5 * dt * (dot(h.ft, vt) - h.ftvt);
    h = {s, f_t, vn, ftvt};
    return f_n + f_t;
  }

  // The contact has ended (no overlap at this step, relative velocity v_rel along the last
  // normal n): books the rest of the last force's work and the energy left in the spring,
  // and clears the history.
  static void finish(const Params& p, const Vec3& n, const Vec3& v_rel, History& h, double dt, Work& work) {
    const double vn = dot(v_rel, n);
    const Vec3 vt = v_rel - vn * n;
    work.damping_n = 0.5 * dt * (p.l3 * p.eta * h.vn) * (vn - h.vn);
    work.friction = 0.5 * p.l3 * p.k * norm2(h.xi) - 0.5 * dt * (dot(h.ft, vt) - h.ftvt);
    h = History{};
  }

  // The registry's parameter reader: [contact] of a case file (law_registry.cpp).
  static Material read(const Section& s);
};

}  // namespace contact
}  // namespace cgdem
