// Force pass of the DEM step: contacts with neighbours and walls, gravity, external force.
//   reads  x, v, omega, radius, species, f_ext, neighbour lists, wall frame
//   writes force, torque, contact histories (xi), per-particle energy accounts
// Each particle sums its own contributions in list order: no shared writes, so the result
// is the same for any number of threads.
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

#pragma omp parallel for schedule(static) if (n >= 512)
  for (int i = 0; i < n; ++i) {
    const Vec3 xi = p.x[i], vi = p.v[i], wi = p.omega[i];
    const double ri = p.radius[i];
    const int si = p.species[i];
    Vec3 f = (1.0 / p.inv_mass[i]) * g + p.f_ext[i];
    Vec3 torque{};
    double e_damp = 0, e_fric = 0, w_wall = 0;

    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int j = nl.partner[e];
      const Vec3 d = xi - p.x[j];
      const double rsum = ri + p.radius[j];
      const double dist2 = norm2(d);
      if (dist2 >= rsum * rsum) {
        nl.xi[e] = Vec3{};  // out of contact: the history ends
        continue;
      }
      const double dist = std::sqrt(dist2);
      const Vec3 nrm = d / dist;  // from j to i
      // Velocity of i's contact point relative to j's.
      const Vec3 v_rel = (vi - p.v[j]) - cross(ri * wi + p.radius[j] * p.omega[j], nrm);
      Vec3 f_t;
      contact::Work w;
      f += contact::force(table.pair(si, p.species[j]), nrm, rsum - dist, v_rel, nl.xi[e], dt, f_t, w);
      torque += cross(-ri * nrm, f_t);
      e_damp += 0.5 * w.damping_n;  // each pair is visited from both sides
      e_fric += 0.5 * w.friction;
    }

    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) {
      const int part = nl.wall_part[e];
      Vec3 grad;
      const double s = frame.part_distance(part, xi, grad);  // eq. (15): phi, grad phi
      if (s >= ri) {
        nl.wall_xi[e] = Vec3{};
        continue;
      }
      const double gl = norm(grad);
      const Vec3 nrm = grad / gl;
      // eq. (16)-(17): overlap (d/2 - phi) along grad phi, scaled by |grad phi| (= 1 for exact SDFs)
      const double delta = (ri - s) * gl;
      const Vec3 u_wall = frame.part_velocity(part);
      const Vec3 v_rel = (vi - u_wall) - cross(ri * wi, nrm);
      Vec3 f_t;
      contact::Work w;
      const Vec3 fc = contact::force(table.wall(si), nrm, delta, v_rel, nl.wall_xi[e], dt, f_t, w);
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
}

}  // namespace cgdem
