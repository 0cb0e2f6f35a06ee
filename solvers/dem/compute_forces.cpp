// Force pass of the DEM step: contacts with neighbours and walls, gravity, external force.
//   reads  x, v, omega, radius, species, f_ext, neighbour lists, wall frame
//   writes force, torque, contact histories (xi), per-particle energy accounts
// Pass 1 (per owner): each listed pair is evaluated once; the owner sums its share, the
// partner's share is stored with the entry. Pass 2 (per particle): the stored shares are
// gathered through the reverse index. No shared writes and every sum in a fixed order,
// so the result is the same for any number of threads. The energy a pair dissipates is
// booked to its owner.
#include <cmath>

#include "solvers/dem/dem_solver.hpp"

namespace cgdem {

void DemSolver::compute_forces() {
  auto scope = timers_.scope(t_force_);
  const int n = static_cast<int>(p_.size());
  const double dt = params_.dt;
  const Vec3 g = params_.gravity;
  Particles& p = p_;
  NeighborList& nl = nl_;
  const ContactTable& table = table_;
  const geometry::Scene::Frame& frame = frame_;

#pragma omp parallel if (n >= 512)
  {
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const Vec3 xi = p.x[i], vi = p.v[i], wi = p.omega[i];
      const double ri = p.radius[i];
      const int si = p.species[i];
      Vec3 f = (1.0 / p.inv_mass[i]) * g + p.f_ext[i];
      Vec3 torque{};
      double e_damp = 0, e_fric = 0, w_wall = 0;

      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int j = nl.partner[e];
        const Vec3 d = xi - (p.x[j] + nl.shift[nl.image[e]]);
        const double rj = p.radius[j];
        const double rsum = ri + rj;
        const double dist2 = norm2(d);
        if (dist2 >= rsum * rsum) {
          // Out of contact: the history ends; book the rest of its last step's work.
          if (!nl.hist[e].empty()) {
            const Vec3 nrm = (1.0 / std::sqrt(dist2)) * d;
            const Vec3 v_rel = (vi - p.v[j]) - cross(ri * wi + rj * p.omega[j], nrm);
            contact::Work w;
            contact::finish(table.pair(si, p.species[j]), nrm, v_rel, nl.hist[e], dt, w);
            e_damp += w.damping_n;
            e_fric += w.friction;
          }
          nl.f_partner[e] = Vec3{};
          nl.t_partner[e] = Vec3{};
          continue;
        }
        const double dist = std::sqrt(dist2);
        const Vec3 nrm = (1.0 / dist) * d;  // from j to i
        // Velocity of i's contact point relative to j's.
        const Vec3 v_rel = (vi - p.v[j]) - cross(ri * wi + rj * p.omega[j], nrm);
        Vec3 f_t;
        contact::Work w;
        const Vec3 fc = contact::force(table.pair(si, p.species[j]), nrm, rsum - dist, v_rel, nl.hist[e], dt, f_t, w);
        const Vec3 nxt = cross(nrm, f_t);
        f += fc;
        torque -= ri * nxt;  // (-r_i n) x F_t
        nl.f_partner[e] = -fc;
        nl.t_partner[e] = nxt;  // the partner's torque is (r_j n) x (-F_t) = -r_j n x F_t
        e_damp += w.damping_n;
        e_fric += w.friction;
      }

      for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) {
        const int part = nl.wall_part[e];
        Vec3 grad;
        const double s = frame.part_distance(part, xi, grad);  // eq. (15): phi, grad phi
        if (s >= ri && nl.wall_hist[e].empty()) continue;
        const double gl = norm(grad);
        const Vec3 nrm = (1.0 / gl) * grad;
        const Vec3 u_wall = frame.part_velocity(part);
        const Vec3 v_rel = (vi - u_wall) - cross(ri * wi, nrm);
        if (s >= ri) {  // the contact has just ended
          contact::Work w;
          contact::finish(table.wall(si), nrm, v_rel, nl.wall_hist[e], dt, w);
          e_damp += w.damping_n;
          e_fric += w.friction;
          continue;
        }
        // eq. (16)-(17): overlap (d/2 - phi) along grad phi, scaled by |grad phi| (= 1 for exact SDFs)
        const double delta = (ri - s) * gl;
        Vec3 f_t;
        contact::Work w;
        const Vec3 fc = contact::force(table.wall(si), nrm, delta, v_rel, nl.wall_hist[e], dt, f_t, w);
        f += fc;
        torque += cross(-ri * nrm, f_t);
        e_damp += w.damping_n;
        e_fric += w.friction;
        w_wall += dot(fc, u_wall) * dt;  // power of the contact force at the wall's velocity
      }

      p.force[i] = f;
      p.torque[i] = torque;
      p.e_damping[i] += e_damp;
      p.e_friction[i] += e_fric;
      p.w_walls[i] += w_wall;
    }

    // Pass 2: the partners' shares, in increasing entry order.
#pragma omp for schedule(static)
    for (int j = 0; j < n; ++j) {
      Vec3 f{}, t{};
      for (int k = nl.rev_offset[j]; k < nl.rev_offset[j + 1]; ++k) {
        const int e = nl.rev_entry[k];
        f += nl.f_partner[e];
        t += nl.t_partner[e];
      }
      p.force[j] += f;
      p.torque[j] -= p.radius[j] * t;
    }
  }
}

}  // namespace cgdem
