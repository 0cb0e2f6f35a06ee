#include "contact/contact_table.hpp"

#include <algorithm>
#include <cmath>

namespace cgdem {

namespace {
double pair_m_eff(const Species& a, const Species& b) {
  double ma = a.original_mass(), mb = b.original_mass();
  return ma * mb / (ma + mb);
}
}  // namespace

ContactTable::ContactTable(const std::vector<Species>& species, const MaterialParams& m)
    : n_(static_cast<int>(species.size())), m_(m), species_(species) {
  pair_.resize(n_ * n_);
  wall_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      double l = std::min(species[i].ratio, species[j].ratio);
      pair_[i * n_ + j] = {m.stiffness,
                           contact::damping_coefficient(m.restitution, pair_m_eff(species[i], species[j]), m.stiffness),
                           m.friction, l * l * l};
    }
    wall_[i] = {m.stiffness,
                contact::damping_coefficient(m.wall_restitution, species[i].original_mass(), m.stiffness),
                m.wall_friction, species[i].l3()};
  }
}

double ContactTable::pair_collision_time(int si, int sj) const {
  return contact::contact_time(m_.restitution, pair_m_eff(species_[si], species_[sj]), m_.stiffness);
}

double ContactTable::wall_collision_time(int s) const {
  return contact::contact_time(m_.wall_restitution, species_[s].original_mass(), m_.stiffness);
}

double ContactTable::min_collision_time() const {
  double t = INFINITY;
  for (int i = 0; i < n_; ++i) {
    t = std::min(t, wall_collision_time(i));
    for (int j = 0; j < n_; ++j) t = std::min(t, pair_collision_time(i, j));
  }
  return t;
}

}  // namespace cgdem
