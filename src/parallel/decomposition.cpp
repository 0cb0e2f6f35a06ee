#include "parallel/decomposition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace cgdem::parallel {

Decomposition::Decomposition(const geometry::Aabb& box, Dims dims, std::array<bool, 3> periodic)
    : box_(box), dims_(dims) {
  long n = 1;
  for (int a = 0; a < 3; ++a) {
    if (dims_[a] < 1)
      throw Error(fmt::format("domain decomposition: {} blocks along {} (dims {} x {} x {}); each axis needs at "
                              "least 1",
                              dims_[a], "xyz"[a], dims_[0], dims_[1], dims_[2]));
    if (!(std::isfinite(box_.lo[a]) && std::isfinite(box_.hi[a]) && box_.hi[a] > box_.lo[a]))
      throw Error(fmt::format("domain decomposition: the box [{:g}, {:g}] m along {} is empty or not finite",
                              box_.lo[a], box_.hi[a], "xyz"[a]));
    n *= dims_[a];
  }
  if (n > std::numeric_limits<int>::max())
    throw Error(fmt::format("domain decomposition: {} x {} x {} blocks is more ranks than an int counts", dims_[0],
                            dims_[1], dims_[2]));
  wrap_.axis = periodic;
  wrap_.lo = box_.lo;
  wrap_.hi = box_.hi;
  for (int a = 0; a < 3; ++a) {
    cut_[a].resize(dims_[a] + 1);
    const double L = box_.hi[a] - box_.lo[a];
    for (int m = 0; m <= dims_[a]; ++m) cut_[a][m] = box_.lo[a] + L * m / dims_[a];
    cut_[a].back() = box_.hi[a];  // exactly, whatever the rounding of L p / p
  }
}

Dims Decomposition::coords_of(int rank) const {
  if (rank < 0 || rank >= ranks())
    throw Error(fmt::format("domain decomposition: rank {} is not one of the {} ranks of {} x {} x {} blocks", rank,
                            ranks(), dims_[0], dims_[1], dims_[2]));
  return {rank % dims_[0], (rank / dims_[0]) % dims_[1], rank / (dims_[0] * dims_[1])};
}

int Decomposition::index_along(int a, double x) const {
  const std::vector<double>& c = cut_[a];
  const int p = dims_[a];
  if (!(x > c.front())) return 0;  // also NaN
  if (x >= c.back()) return p - 1;
  int m = std::clamp(static_cast<int>((x - c.front()) / (c.back() - c.front()) * p), 0, p - 1);
  // The quotient can round across a cut: settle against the cut values themselves, so
  // that owner_of() and block() never disagree on a point lying on a cut.
  while (m > 0 && x < c[m]) --m;
  while (m < p - 1 && x >= c[m + 1]) ++m;
  return m;
}

int Decomposition::owner_of(const Vec3& x) const {
  Vec3 y = x;
  wrap_.wrap(y);
  return rank_of({index_along(0, y.x), index_along(1, y.y), index_along(2, y.z)});
}

bool Decomposition::contains(const Vec3& x) const {
  for (int a = 0; a < 3; ++a) {
    const bool inside = wrap_.axis[a] ? std::isfinite(x[a]) : (x[a] >= box_.lo[a] && x[a] <= box_.hi[a]);
    if (!inside) return false;
  }
  return true;
}

geometry::Aabb Decomposition::block(int rank) const {
  const Dims c = coords_of(rank);
  geometry::Aabb b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = cut_[a][c[a]];
    b.hi[a] = cut_[a][c[a] + 1];
  }
  return b;
}

std::vector<int> Decomposition::neighbours(int rank) const {
  const Dims c = coords_of(rank);
  std::vector<int> out;
  for (int d = 0; d < 27; ++d) {
    const Dims step = {d % 3 - 1, (d / 3) % 3 - 1, d / 9 - 1};
    if (step == Dims{0, 0, 0}) continue;
    Dims n;
    bool exists = true;
    for (int a = 0; a < 3; ++a) {
      n[a] = c[a] + step[a];
      if (n[a] >= 0 && n[a] < dims_[a]) continue;
      if (wrap_.axis[a])
        n[a] = (n[a] + dims_[a]) % dims_[a];
      else
        exists = false;
    }
    if (exists && rank_of(n) != rank) out.push_back(rank_of(n));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Dims choose_dims(int n_ranks, const Vec3& extent) {
  if (n_ranks < 1) throw Error(fmt::format("domain decomposition: {} ranks; at least 1 is needed", n_ranks));
  if (!(extent.x > 0 && extent.y > 0 && extent.z > 0 && std::isfinite(extent.x) && std::isfinite(extent.y) &&
        std::isfinite(extent.z)))
    throw Error(fmt::format("domain decomposition: box extent ({:g}, {:g}, {:g}) m must be positive and finite",
                            extent.x, extent.y, extent.z));
  const Vec3 section{extent.y * extent.z, extent.x * extent.z, extent.x * extent.y};  // normal to x, y, z
  Dims best{n_ranks, 1, 1};
  double best_area = INFINITY;
  for (int px = n_ranks; px >= 1; --px) {
    if (n_ranks % px) continue;
    for (int py = n_ranks / px; py >= 1; --py) {
      if ((n_ranks / px) % py) continue;
      const int pz = n_ranks / px / py;
      const double area = (px - 1) * section.x + (py - 1) * section.y + (pz - 1) * section.z;
      if (area < best_area) {
        best_area = area;
        best = {px, py, pz};
      }
    }
  }
  return best;
}

}  // namespace cgdem::parallel
