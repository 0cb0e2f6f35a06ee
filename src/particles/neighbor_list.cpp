#include "particles/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cgdem {

namespace {

struct CellGrid {
  Vec3 lo;
  double h = 1;
  int n[3] = {1, 1, 1};
  int cell_of(const Vec3& x) const {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((x[a] - lo[a]) / h), 0, n[a] - 1);
    return c[0] + n[0] * (c[1] + n[1] * c[2]);
  }
};

}  // namespace

void NeighborList::build(Particles& p, const geometry::Scene::Frame& walls) {
  const int np = static_cast<int>(p.size());
  ++builds;

  // 1. Cell grid over the particles' bounding box, cells at least one interaction range wide.
  CellGrid g;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
  double rmax = 0;
  for (int i = 0; i < np; ++i) {
    lo = cmin(lo, p.x[i]);
    hi = cmax(hi, p.x[i]);
    rmax = std::max(rmax, p.radius[i]);
  }
  if (np == 0) lo = hi = Vec3{};
  g.h = 2 * rmax + skin;
  if (!(g.h > 0)) g.h = 1;
  g.lo = lo;
  for (int a = 0; a < 3; ++a) g.n[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / g.h) + 1);
  const long ncell = static_cast<long>(g.n[0]) * g.n[1] * g.n[2];

  // 2. Counting sort of the particles by cell; order[new] = old.
  std::vector<int> cell(np), start(ncell + 1, 0);
  for (int i = 0; i < np; ++i) ++start[(cell[i] = g.cell_of(p.x[i])) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(np), fill(start.begin(), start.end() - 1);
  for (int i = 0; i < np; ++i) order[fill[cell[i]]++] = i;
  std::vector<int> new_of_old(np);
  for (int i = 0; i < np; ++i) new_of_old[order[i]] = i;
  p.reorder(order);

  // Old lists (in old indices), kept for the history carry-over.
  std::vector<int> old_off, old_partner, old_woff, old_wpart;
  std::vector<Vec3> old_xi, old_wxi;
  old_off.swap(offset);
  old_partner.swap(partner);
  old_xi.swap(xi);
  old_woff.swap(wall_offset);
  old_wpart.swap(wall_part);
  old_wxi.swap(wall_xi);
  const bool have_old = old_off.size() == static_cast<size_t>(np) + 1;

  // 3. Pair lists: count, then fill, each particle scanning the 27 cells in a fixed order.
  auto for_neighbours = [&](int i, auto&& visit) {
    const Vec3& xi_ = p.x[i];
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((xi_[a] - g.lo[a]) / g.h), 0, g.n[a] - 1);
    for (int dz = -1; dz <= 1; ++dz) {
      int cz = c[2] + dz;
      if (cz < 0 || cz >= g.n[2]) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = c[1] + dy;
        if (cy < 0 || cy >= g.n[1]) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = c[0] + dx;
          if (cx < 0 || cx >= g.n[0]) continue;
          long cc = cx + static_cast<long>(g.n[0]) * (cy + static_cast<long>(g.n[1]) * cz);
          for (int j = start[cc]; j < start[cc + 1]; ++j) {
            if (j == i) continue;
            double reach = p.radius[i] + p.radius[j] + skin;
            if (norm2(p.x[j] - xi_) < reach * reach) visit(j);
          }
        }
      }
    }
  };
  offset.assign(np + 1, 0);
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < np; ++i) {
    int count = 0;
    for_neighbours(i, [&](int) { ++count; });
    offset[i + 1] = count;
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  partner.resize(offset[np]);
  xi.assign(offset[np], Vec3{});
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < np; ++i) {
    int e = offset[i];
    for_neighbours(i, [&](int j) { partner[e++] = j; });
    std::sort(partner.begin() + offset[i], partner.begin() + offset[i + 1]);
    if (!have_old) continue;
    // Carry the history over: look the partner up in the old list of the same particle.
    const int oi = order[i];
    for (int k = old_off[oi]; k < old_off[oi + 1]; ++k) {
      if (old_xi[k] == Vec3{}) continue;
      const int nj = new_of_old[old_partner[k]];
      auto first = partner.begin() + offset[i], last = partner.begin() + offset[i + 1];
      auto it = std::lower_bound(first, last, nj);
      if (it != last && *it == nj) xi[it - partner.begin()] = old_xi[k];
    }
  }

  // 4. Wall candidates: parts whose surface is within r + skin of the particle.
  const int nparts = static_cast<int>(walls.scene ? walls.scene->parts().size() : 0);
  std::vector<geometry::Aabb> part_box(nparts);
  for (int q = 0; q < nparts; ++q) part_box[q] = walls.part_bounds(q);
  wall_offset.assign(np + 1, 0);
  std::vector<std::vector<int>> cand(np);
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < np; ++i) {
    const double reach = p.radius[i] + skin;
    for (int q = 0; q < nparts; ++q)
      if (part_box[q].distance(p.x[i]) < reach && walls.part_distance(q, p.x[i]) < reach) cand[i].push_back(q);
    wall_offset[i + 1] = static_cast<int>(cand[i].size());
  }
  std::partial_sum(wall_offset.begin(), wall_offset.end(), wall_offset.begin());
  wall_part.resize(wall_offset[np]);
  wall_xi.assign(wall_offset[np], Vec3{});
  for (int i = 0; i < np; ++i) {
    std::copy(cand[i].begin(), cand[i].end(), wall_part.begin() + wall_offset[i]);
    if (!have_old) continue;
    const int oi = order[i];
    for (int k = old_woff[oi]; k < old_woff[oi + 1]; ++k)
      for (int e = wall_offset[i]; e < wall_offset[i + 1]; ++e)
        if (wall_part[e] == old_wpart[k]) wall_xi[e] = old_wxi[k];
  }

  x_at_build = p.x;
  body_offset_at_build = walls.offset;
}

bool NeighborList::needs_rebuild(const Particles& p, const geometry::Scene::Frame& walls) const {
  if (x_at_build.size() != p.size()) return true;
  double wall_move = 0;
  for (size_t b = 0; b < walls.offset.size() && b < body_offset_at_build.size(); ++b)
    wall_move = std::max(wall_move, norm(walls.offset[b] - body_offset_at_build[b]));
  const double limit2 = 0.25 * skin * skin;
  const int np = static_cast<int>(p.size());
  // Pairs: each particle may have moved up to skin/2. Walls: particle + wall motion.
  const double wall_limit = 0.5 * skin - wall_move;
  if (wall_limit <= 0) return true;
  const double wl2 = wall_limit * wall_limit;
  int flag = 0;
#pragma omp parallel for schedule(static) reduction(| : flag) if (np >= 512)
  for (int i = 0; i < np; ++i) {
    double d2 = norm2(p.x[i] - x_at_build[i]);
    if (d2 > limit2 || d2 > wl2) flag = 1;
  }
  return flag != 0;
}

}  // namespace cgdem
