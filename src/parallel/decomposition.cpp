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

Decomposition::Decomposition(const geometry::Aabb& box, const Cuts& cuts, std::array<bool, 3> periodic)
    : Decomposition(box, Dims{static_cast<int>(std::max<size_t>(cuts[0].size(), 2) - 1),
                              static_cast<int>(std::max<size_t>(cuts[1].size(), 2) - 1),
                              static_cast<int>(std::max<size_t>(cuts[2].size(), 2) - 1)},
                    periodic) {
  for (int a = 0; a < 3; ++a) {
    const std::vector<double>& c = cuts[a];
    if (c.size() < 2 || c.front() != box_.lo[a] || c.back() != box_.hi[a])
      throw Error(fmt::format("domain decomposition: the cuts along {} must run from the box's {:g} to {:g} m", "xyz"[a],
                              box_.lo[a], box_.hi[a]));
    for (size_t m = 1; m < c.size(); ++m)
      if (!(c[m] > c[m - 1]))
        throw Error(fmt::format("domain decomposition: the cuts along {} must increase strictly ({:g} then {:g} m)",
                                "xyz"[a], c[m - 1], c[m]));
    cut_[a] = c;
  }
  uniform_ = false;
}

double Decomposition::narrowest_block() const {
  double w = INFINITY;
  for (int a = 0; a < 3; ++a)
    for (size_t m = 1; m < cut_[a].size(); ++m) w = std::min(w, cut_[a][m] - cut_[a][m - 1]);
  return w;
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
  if (!uniform_)  // the block m with c[m] <= x < c[m+1]
    return static_cast<int>(std::upper_bound(c.begin() + 1, c.end() - 1, x) - (c.begin() + 1));
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

Decomposition::Cuts balanced_cuts(const geometry::Aabb& box, Dims dims, const std::vector<Vec3>& points,
                                  double min_width) {
  Decomposition::Cuts cuts;
  for (int a = 0; a < 3; ++a) {
    const int p = dims[a];
    const double lo = box.lo[a], hi = box.hi[a];
    if (p < 1) throw Error(fmt::format("domain decomposition: {} blocks along {}", p, "xyz"[a]));
    if (p * min_width > hi - lo)
      throw Error(fmt::format("domain decomposition: {} blocks along {} of at least {:.4g} m (one interaction range) "
                              "do not fit in the box's {:.4g} m; use fewer ranks",
                              p, "xyz"[a], min_width, hi - lo));
    std::vector<double> v;
    v.reserve(points.size());
    for (const Vec3& x : points)
      if (std::isfinite(x[a])) v.push_back(std::clamp(x[a], lo, hi));
    std::sort(v.begin(), v.end());
    std::vector<double>& c = cuts[a];
    c.assign(p + 1, lo);
    c[p] = hi;
    for (int m = 1; m < p; ++m) {
      double q = lo + (hi - lo) * m / p;  // no points: even
      if (!v.empty()) {
        const size_t k = std::min(v.size() - 1, v.size() * static_cast<size_t>(m) / static_cast<size_t>(p));
        q = k > 0 ? 0.5 * (v[k - 1] + v[k]) : v[k];
      }
      c[m] = q;
    }
    // At least min_width apart, and inside [lo + m w, hi - (p - m) w]: forward, then back.
    for (int m = 1; m < p; ++m) c[m] = std::max(c[m], c[m - 1] + min_width);
    for (int m = p - 1; m >= 1; --m) c[m] = std::min(c[m], c[m + 1] - min_width);
  }
  return cuts;
}

}  // namespace cgdem::parallel
