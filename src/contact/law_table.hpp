// Contact parameters of one law for every species pair and every species-wall combination.
//
// For parcels of ratios l_i, l_j the number of simultaneous original contacts is taken as
// min(l_i, l_j)^3 (equal ratios: l^3 as in eq. 6); the ORIGINAL pair's reduced mass
// m_O,i m_O,j / (m_O,i + m_O,j) (wall: m_O) and reduced radius (wall: r_O) go to the law,
// so that e and t_c do not depend on l (docs/model.md, section 1).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/history.hpp"
#include "particles/species.hpp"

namespace cgdem::contact {

inline OriginalPair original_pair(const Species& a, const Species& b) {
  const double l = std::min(a.ratio, b.ratio);
  const double ma = a.original_mass(), mb = b.original_mass();
  const double ra = 0.5 * a.d_original, rb = 0.5 * b.d_original;
  return {l * l * l, ma * mb / (ma + mb), ra * rb / (ra + rb), false};
}
inline OriginalPair original_wall_pair(const Species& s) {
  return {s.l3(), s.original_mass(), 0.5 * s.d_original, true};
}

template <class L>
class LawTable {
 public:
  using Law = L;
  using Material = typename Law::Material;
  using Params = typename Law::Params;

  LawTable() = default;
  LawTable(const std::vector<Species>& species, const Material& m)
      : n_(static_cast<int>(species.size())), m_(m), species_(species) {
    pair_.resize(n_ * n_);
    wall_.resize(n_);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) pair_[i * n_ + j] = Law::params(m, original_pair(species[i], species[j]));
      wall_[i] = Law::params(m, original_wall_pair(species[i]));
    }
  }
  const Params& pair(int si, int sj) const { return pair_[si * n_ + sj]; }
  const Params& wall(int s) const { return wall_[s]; }
  int species_count() const { return n_; }
  const Material& material() const { return m_; }
  // Collision times of the original contacts (equal to the parcels' for equal l).
  double pair_collision_time(int si, int sj) const {
    return Law::collision_time(m_, original_pair(species_[si], species_[sj]));
  }
  double wall_collision_time(int s) const { return Law::collision_time(m_, original_wall_pair(species_[s])); }
  double min_collision_time() const {
    double t = INFINITY;
    for (int i = 0; i < n_; ++i) {
      t = std::min(t, wall_collision_time(i));
      for (int j = 0; j < n_; ++j) t = std::min(t, pair_collision_time(i, j));
    }
    return t;
  }

 private:
  int n_ = 0;
  Material m_{};
  std::vector<Species> species_;
  std::vector<Params> pair_, wall_;
};

}  // namespace cgdem::contact
