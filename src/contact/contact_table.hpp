// Contact parameters for every species pair and every species-wall combination.
//
// For parcels of ratios l_i, l_j the number of simultaneous original contacts is taken as
// min(l_i, l_j)^3 (equal ratios: l^3 as in eq. 6); the damping uses the ORIGINAL pair's
// effective mass m_O,i m_O,j / (m_O,i + m_O,j) (wall: m_O), so e and t_c do not depend on l.
#pragma once
#include <vector>

#include "contact/contact_law.hpp"
#include "particles/species.hpp"

namespace cgdem {

struct MaterialParams {
  double stiffness = 50;        // k [N/m]
  double restitution = 0.9;     // e, particle-particle
  double friction = 0.3;        // mu, particle-particle
  double wall_restitution = 0.9;
  double wall_friction = 0.3;
};

class ContactTable {
 public:
  ContactTable() = default;
  ContactTable(const std::vector<Species>& species, const MaterialParams& m);
  const contact::Params& pair(int si, int sj) const { return pair_[si * n_ + sj]; }
  const contact::Params& wall(int s) const { return wall_[s]; }
  int species_count() const { return n_; }
  // Collision times of the original contacts (equal to the parcels' for equal l).
  double pair_collision_time(int si, int sj) const;
  double wall_collision_time(int s) const;
  double min_collision_time() const;

 private:
  int n_ = 0;
  MaterialParams m_;
  std::vector<Species> species_;
  std::vector<contact::Params> pair_, wall_;
};

}  // namespace cgdem
