// Energy budget of the particle system (serial, fixed order: thread-count independent).
//   E_kin = sum 1/2 m v^2 + 1/2 I w^2,   E_pot = - sum m g . x
//   E_el  = sum over contacts of the law's elastic energy (linear: 1/2 l^3 k (delta^2 + |xi|^2))
//   E_rot,O = sum 1/2 (I / l^2) w^2: the l^3 originals of a parcel, each with I_O = I / l^5
//             (eq. 5) and the parcel's w, hold l^3 I_O w^2 / 2 = (I w^2 / 2) / l^2.
#include "solvers/dem/dem_solver.hpp"

#include <limits>

namespace cgdem {

// The energy held by the springs of this rank's contacts (a pair with a ghost counted on
// the rank of its lower id), in a fixed order: particles, then each one's pairs and walls.
template <class Law>
double DemSolver::elastic_energy(const contact::LawTable<Law>& table) const {
  const Particles& p = p_;
  const size_t n = owned();
  double elastic = 0;
  for (size_t i = 0; i < n; ++i) {
    for (int e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e) {
      const int j = nl_.partner[e];
      if (static_cast<size_t>(j) >= n && p.id[j] < p.id[i]) continue;
      const double overlap = p.radius[i] + p.radius[j] - norm(p.x[i] - nl_.partner_x(p, e));
      if (overlap <= 0) continue;
      elastic += Law::elastic_energy(table.pair(p.species[i], p.species[j]), overlap, Law::unpack(nl_.hist.get(e)));
    }
    for (int e = nl_.wall_offset[i]; e < nl_.wall_offset[i + 1]; ++e) {
      const double overlap = p.radius[i] - frame_.part_distance(nl_.wall_part[e], p.x[i]);
      if (overlap <= 0) continue;
      elastic += Law::elastic_energy(table.wall(p.species[i]), overlap, Law::unpack(nl_.wall_hist[e]));
    }
  }
  return elastic;
}

EnergyBudget DemSolver::energy() const {
  EnergyBudget b;
  const Particles& p = p_;
  // This rank's parcels (all of them without MPI); a pair with a ghost is counted on the
  // rank of its lower id, so that the sum over the ranks counts it once.
  const size_t n = owned();
  for (size_t i = 0; i < n; ++i) {
    const double m = 1.0 / p.inv_mass[i], I = 1.0 / p.inv_inertia[i];
    b.kinetic_translational += 0.5 * m * norm2(p.v[i]);
    b.kinetic_rotational += 0.5 * I * norm2(p.omega[i]);
    const double l = species_[p.species[i]].ratio;
    b.kinetic_rotational_originals += 0.5 * I / (l * l) * norm2(p.omega[i]);  // eq. (5): l^3 I_O = I / l^2
    b.potential -= m * dot(params_.gravity, p.x[i]);
    b.momentum += m * p.v[i];
    b.mass += m;
    b.dissipated_damping += p.e_damping[i];
    b.dissipated_friction += p.e_friction[i];
    b.work_walls += p.w_walls[i];
  }
  if (nl_.valid_for(p))
    b.elastic = std::visit([this](const auto& table) { return elastic_energy(table); }, tables_);
  b.dissipated_damping += removed_damping_;
  b.dissipated_friction += removed_friction_;
  b.work_walls += removed_walls_;
  if (!params_.accounts)  // not computed (and balance() with them)
    b.dissipated_damping = b.dissipated_friction = b.work_walls = std::numeric_limits<double>::quiet_NaN();
  return b;
}

double DemSolver::fluid_work() const {
  double w = removed_fluid_;
  for (size_t i = 0; i < owned(); ++i) w += p_.w_fluid[i];
  return w;
}

}  // namespace cgdem
