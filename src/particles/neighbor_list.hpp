// Verlet neighbour lists built from a cell list, with contact history attached.
//
// Full lists: every pair (i, j) appears in i's list and in j's list, so each particle
// sums its own forces in a fixed order and the result is independent of the number of
// threads (the contact law is exactly antisymmetric, contact_law.hpp). A pair is listed
// when |x_i - x_j| < r_i + r_j + skin; the lists stay valid until some particle has moved
// more than skin/2 (plus the largest wall displacement, for wall candidates).
//
// build() also sorts the particles along the cell grid (better cache use) and carries
// the tangential history of every pair and every particle-wall contact over to the new
// lists, by particle identity.
#pragma once
#include <vector>

#include "geometry/scene.hpp"
#include "particles/particles.hpp"

namespace cgdem {

struct NeighborList {
  double skin = 0;
  // Particle pairs (CSR): entries offset[i] .. offset[i+1]-1 of `partner` and `xi`.
  std::vector<int> offset, partner;
  std::vector<Vec3> xi;  // tangential spring displacement of the contact
  // Particle-wall candidates (CSR over wall parts).
  std::vector<int> wall_offset, wall_part;
  std::vector<Vec3> wall_xi;
  // State at the last build, for the rebuild criterion.
  std::vector<Vec3> x_at_build;
  std::vector<Vec3> body_offset_at_build;
  long builds = 0;

  // Sorts `p` (dropping nothing), rebuilds both lists and carries history over.
  void build(Particles& p, const geometry::Scene::Frame& walls);
  // True when the lists may have become incomplete.
  bool needs_rebuild(const Particles& p, const geometry::Scene::Frame& walls) const;
  size_t pair_entries() const { return partner.size(); }
};

}  // namespace cgdem
