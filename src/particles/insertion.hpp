// Random insertion of non-overlapping spheres in a box, reproducible from a seed.
// Candidates are drawn uniformly in [lo + r, hi - r] and rejected when they overlap a
// particle already present or a wall (phi < r). Throws cgdem::Error if `count` spheres do
// fit: max_attempts candidates in a row rejected (the region is too full).
#pragma once
#include <cstdint>

#include "geometry/scene.hpp"
#include "particles/particles.hpp"

namespace cgdem {

struct InsertRegion {
  Vec3 lo, hi;
  long count = 0;
  int species = 0;
  Vec3 velocity{};
};

// Appends to `p`; ids continue from next_id. Returns the number inserted (= count).
long insert_random(Particles& p, const std::vector<Species>& species, const InsertRegion& region,
                   const geometry::Scene::Frame& walls, uint64_t seed, int64_t next_id, long max_attempts = 0);

}  // namespace cgdem
