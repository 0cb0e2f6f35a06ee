#include "particles/insertion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

#include "core/error.hpp"

namespace cgdem {

long insert_random(Particles& p, const std::vector<Species>& species, const InsertRegion& region,
                   const geometry::Scene::Frame& walls, uint64_t seed, int64_t next_id, long max_attempts) {
  const Species& s = species.at(region.species);
  const double r = 0.5 * s.diameter();
  double rmax = r;
  for (double rr : p.radius) rmax = std::max(rmax, rr);
  const Vec3 lo = region.lo + Vec3{r, r, r}, hi = region.hi - Vec3{r, r, r};
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    throw Error(fmt::format("insertion region is smaller than one particle of species '{}'", s.name));
  if (max_attempts <= 0) max_attempts = 200000;  // consecutive failures before giving up

  // Hash grid of existing and new particles, cell = 2 rmax.
  const double h = 2 * rmax;
  auto key = [&](const Vec3& x) {
    int64_t i = static_cast<int64_t>(std::floor(x.x / h)), j = static_cast<int64_t>(std::floor(x.y / h)),
            k = static_cast<int64_t>(std::floor(x.z / h));
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  std::unordered_multimap<int64_t, int> grid;
  for (size_t i = 0; i < p.size(); ++i) grid.emplace(key(p.x[i]), static_cast<int>(i));

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  long placed = 0, attempts = 0;  // attempts since the last success
  while (placed < region.count) {
    if (++attempts > max_attempts)
      throw Error(fmt::format("could place only {} of {} particles of species '{}' in the region [{:g},{:g},{:g}]-[{:g},{:g},{:g}] "
                              "({} attempts in a row failed: the solid fraction is too high for random insertion)",
                              placed, region.count, s.name, region.lo.x, region.lo.y, region.lo.z, region.hi.x,
                              region.hi.y, region.hi.z, max_attempts));
    Vec3 x{ux(rng), uy(rng), uz(rng)};
    if (walls.scene && !walls.scene->empty() && walls.phi(x) < r) continue;
    bool free = true;
    for (int dk = -1; dk <= 1 && free; ++dk)
      for (int dj = -1; dj <= 1 && free; ++dj)
        for (int di = -1; di <= 1 && free; ++di) {
          auto range = grid.equal_range(key(x + Vec3{di * h, dj * h, dk * h}));
          for (auto it = range.first; it != range.second; ++it) {
            double rs = r + p.radius[it->second];
            if (norm2(p.x[it->second] - x) < rs * rs) {
              free = false;
              break;
            }
          }
        }
    if (!free) continue;
    p.add(next_id + placed, region.species, s, x, region.velocity);
    grid.emplace(key(x), static_cast<int>(p.size() - 1));
    ++placed;
    attempts = 0;
  }
  return placed;
}

}  // namespace cgdem
