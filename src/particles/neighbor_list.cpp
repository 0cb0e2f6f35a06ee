#include "particles/neighbor_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"

namespace cgdem {

void Periodicity::wrap(Vec3& x) const {
  for (int a = 0; a < 3; ++a) {
    if (!axis[a]) continue;
    const double L = hi[a] - lo[a];
    double t = x[a] - lo[a];
    t -= L * std::floor(t / L);
    if (t >= L) t = 0;  // rounding of a value just below lo
    x[a] = lo[a] + t;
  }
}

namespace {

struct CellGrid {
  Vec3 lo;
  double h[3] = {1, 1, 1};
  int n[3] = {1, 1, 1};
  void coords(const Vec3& x, int c[3]) const {
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((x[a] - lo[a]) / h[a]), 0, n[a] - 1);
  }
  long index(int cx, int cy, int cz) const { return cx + static_cast<long>(n[0]) * (cy + static_cast<long>(n[1]) * cz); }
};

constexpr int kNoImage = 13;  // image code (sx+1) + 3 (sy+1) + 9 (sz+1) with s = 0

// The entry of pair (owner, other), owner < other, or -1: pair lists are sorted by partner.
int find_entry(const std::vector<int>& off, const std::vector<int>& partner, int owner, int other) {
  auto first = partner.begin() + off[owner], last = partner.begin() + off[owner + 1];
  auto it = std::lower_bound(first, last, other);
  return it == last || *it != other ? -1 : static_cast<int>(it - partner.begin());
}

// Entry of the old history, in old indices.
const contact::History* find_history(const std::vector<int>& off, const std::vector<int>& partner,
                                     const std::vector<contact::History>& xi,
                         int owner, int other) {
  const int e = find_entry(off, partner, owner, other);
  return e < 0 ? nullptr : &xi[e];
}

// (id, local index) sorted by id, to find carried histories' particles; ids must be unique.
std::vector<std::pair<int64_t, int>> index_by_id(const std::vector<int64_t>& id) {
  std::vector<std::pair<int64_t, int>> by_id(id.size());
  for (size_t i = 0; i < id.size(); ++i) by_id[i] = {id[i], static_cast<int>(i)};
  std::sort(by_id.begin(), by_id.end());
  for (size_t k = 1; k < by_id.size(); ++k)
    if (by_id[k].first == by_id[k - 1].first)
      throw Error(fmt::format("neighbour list: particle id {} is held twice (local indices {} and {}); ids must be "
                              "unique to attach carried contact history",
                              by_id[k].first, by_id[k - 1].second, by_id[k].second));
  return by_id;
}

int local_index(const std::vector<std::pair<int64_t, int>>& by_id, int64_t id) {
  auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair<int64_t, int>{id, -1});
  return it != by_id.end() && it->first == id ? it->second : -1;
}

}  // namespace

void NeighborList::build(Particles& p, const geometry::Scene::Frame& walls) {
  const int np = static_cast<int>(p.size());
  if (ghosts > p.size())
    throw Error(fmt::format("neighbour list: {} ghosts among {} particles", ghosts, p.size()));
  if (ghosts > 0 && periodic.any())
    throw Error("neighbour list: ghost parcels on periodic axes are not supported (their periodic images would be "
                "missing)");
  // Owned particles 0..no-1, ghosts no..np-1 (no = np without ghosts: the serial path).
  const int no = np - static_cast<int>(ghosts);
  ++builds;
  if (periodic.any())
    for (int i = 0; i < np; ++i) periodic.wrap(p.x[i]);

  // 1. Cell grid over the particles' bounding box (the period on periodic axes), cells at
  //    least one interaction range wide. Ghosts are in the box: pairs with them are found
  //    through the same grid.
  CellGrid g;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
  double rmax = 0;
  for (int i = 0; i < np; ++i) {
    lo = cmin(lo, p.x[i]);
    hi = cmax(hi, p.x[i]);
    rmax = std::max(rmax, p.radius[i]);
  }
  if (np == 0) lo = hi = Vec3{};
  double range = 2 * rmax + skin;
  if (!(range > 0)) range = 1;
  for (int a = 0; a < 3; ++a) {
    if (periodic.axis[a]) {
      const double L = periodic.hi[a] - periodic.lo[a];
      g.lo[a] = periodic.lo[a];
      g.n[a] = static_cast<int>(L / range);
      if (g.n[a] < 3)
        throw RunError(fmt::format("periodic length {:.4g} m along axis {} is shorter than three interaction ranges "
                                   "(3 x {:.4g} m: largest diameter plus skin)",
                                   L, "xyz"[a], range));
      g.h[a] = L / g.n[a];
    } else {
      g.lo[a] = lo[a];
      g.h[a] = range;
      g.n[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / range) + 1);
    }
  }
  for (int c = 0; c < 27; ++c) {
    const int s[3] = {c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1};
    for (int a = 0; a < 3; ++a) shift[c][a] = periodic.axis[a] ? s[a] * (periodic.hi[a] - periodic.lo[a]) : 0.0;
  }
  const long ncell = static_cast<long>(g.n[0]) * g.n[1] * g.n[2];

  // 2. Counting sort of the owned particles by cell; order[new] = old. Ghosts keep their
  //    places (order is the identity on them: the halo exchange fills them in the order it
  //    appended them) and get a cell index of their own: ghost_in[ghost_start[c] ..
  //    ghost_start[c+1]-1] are the ghosts in cell c.
  std::vector<long> cell(np);
  std::vector<int> start(ncell + 1, 0);
  for (int i = 0; i < no; ++i) {
    int c[3];
    g.coords(p.x[i], c);
    ++start[(cell[i] = g.index(c[0], c[1], c[2])) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(np), fill(start.begin(), start.end() - 1);
  for (int i = 0; i < no; ++i) order[fill[cell[i]]++] = i;
  for (int i = no; i < np; ++i) order[i] = i;
  std::vector<int> ghost_start, ghost_in;
  if (no < np) {
    ghost_start.assign(ncell + 1, 0);
    for (int i = no; i < np; ++i) {
      int c[3];
      g.coords(p.x[i], c);
      ++ghost_start[(cell[i] = g.index(c[0], c[1], c[2])) + 1];
    }
    std::partial_sum(ghost_start.begin(), ghost_start.end(), ghost_start.begin());
    ghost_in.resize(np - no);
    std::vector<int> gfill(ghost_start.begin(), ghost_start.end() - 1);
    for (int i = no; i < np; ++i) ghost_in[gfill[cell[i]]++] = i;
  }
  p.reorder(order);

  // Old lists (in old indices), kept for the history carry-over.
  std::vector<int> old_off, old_partner, old_woff, old_wpart;
  std::vector<contact::History> old_xi, old_wxi;
  old_off.swap(offset);
  old_partner.swap(partner);
  old_xi.swap(hist);
  old_woff.swap(wall_offset);
  old_wpart.swap(wall_part);
  old_wxi.swap(wall_hist);
  const bool have_old = old_off.size() == static_cast<size_t>(np) + 1;

  // 3. Half pair lists: count, then fill; each owned particle scans the 27 cells in a
  //    fixed order and keeps partners with a higher index, then the ghosts of those cells
  //    (all above it). Ghosts own no entries.
  auto for_neighbours = [&](int i, auto&& visit) {
    const Vec3& x0 = p.x[i];
    int c[3];
    g.coords(x0, c);
    for (int dz = -1; dz <= 1; ++dz) {
      int cz = c[2] + dz, sz = 0;
      if (cz < 0 || cz >= g.n[2]) {
        if (!periodic.axis[2]) continue;
        sz = cz < 0 ? -1 : 1;
        cz -= sz * g.n[2];
      }
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = c[1] + dy, sy = 0;
        if (cy < 0 || cy >= g.n[1]) {
          if (!periodic.axis[1]) continue;
          sy = cy < 0 ? -1 : 1;
          cy -= sy * g.n[1];
        }
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = c[0] + dx, sx = 0;
          if (cx < 0 || cx >= g.n[0]) {
            if (!periodic.axis[0]) continue;
            sx = cx < 0 ? -1 : 1;
            cx -= sx * g.n[0];
          }
          const int code = (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1);
          const long cc = g.index(cx, cy, cz);
          for (int j = std::max(start[cc], i + 1); j < start[cc + 1]; ++j) {
            const double reach = p.radius[i] + p.radius[j] + skin;
            if (norm2(p.x[j] + shift[code] - x0) < reach * reach) visit(j, code);
          }
          if (no < np)
            for (int k = ghost_start[cc]; k < ghost_start[cc + 1]; ++k) {
              const int j = ghost_in[k];
              const double reach = p.radius[i] + p.radius[j] + skin;
              if (norm2(p.x[j] + shift[code] - x0) < reach * reach) visit(j, code);
            }
        }
      }
    }
  };
  offset.assign(np + 1, 0);
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < no; ++i) {
    int count = 0;
    for_neighbours(i, [&](int, int) { ++count; });
    offset[i + 1] = count;
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  const int ne = offset[np];
  partner.resize(ne);
  image.resize(ne);
  hist.assign(ne, contact::History{});
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < no; ++i) {
    std::vector<std::pair<int, int>> found;
    found.reserve(offset[i + 1] - offset[i]);
    for_neighbours(i, [&](int j, int code) { found.emplace_back(j, code); });
    std::sort(found.begin(), found.end());
    for (int k = 0, e = offset[i]; e < offset[i + 1]; ++e, ++k) {
      partner[e] = found[k].first;
      image[e] = static_cast<uint8_t>(found[k].second);
      if (!have_old) continue;
      // History of the same pair: under the lower of the two old indices, in its frame.
      const int oi = order[i], oj = order[found[k].first];
      if (oi < oj) {
        if (const auto* h = find_history(old_off, old_partner, old_xi, oi, oj)) hist[e] = *h;
      } else {
        if (const auto* h = find_history(old_off, old_partner, old_xi, oj, oi)) hist[e] = h->flipped();
      }
    }
  }
  // Histories carried in from other ranks; an empty `incoming` costs nothing here.
  std::vector<std::pair<int64_t, int>> by_id;
  if (!incoming.empty()) by_id = index_by_id(p.id);
  for (const CarriedPair& c : incoming.pairs) {
    const int a = local_index(by_id, c.id_a), b = local_index(by_id, c.id_b);
    if (a < 0 || b < 0 || a == b) continue;
    const int e = find_entry(offset, partner, std::min(a, b), std::max(a, b));
    if (e >= 0) hist[e] = a < b ? c.h : c.h.flipped();  // the owner is the lower index
  }
  // Reverse index, entries in increasing order for each partner.
  rev_offset.assign(np + 1, 0);
  for (int e = 0; e < ne; ++e) ++rev_offset[partner[e] + 1];
  std::partial_sum(rev_offset.begin(), rev_offset.end(), rev_offset.begin());
  rev_entry.resize(ne);
  {
    std::vector<int> pos(rev_offset.begin(), rev_offset.end() - 1);
    for (int e = 0; e < ne; ++e) rev_entry[pos[partner[e]]++] = e;
  }
  derive();

  // 4. Wall candidates: parts whose surface is within r + skin of the particle (owned
  //    particles only: a ghost's wall contacts are its owner's).
  const int nparts = static_cast<int>(walls.scene ? walls.scene->parts().size() : 0);
  std::vector<geometry::Aabb> part_box(nparts);
  for (int q = 0; q < nparts; ++q) part_box[q] = walls.part_bounds(q);
  wall_offset.assign(np + 1, 0);
  std::vector<std::vector<int>> cand(np);
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < no; ++i) {
    const double reach = p.radius[i] + skin;
    for (int q = 0; q < nparts; ++q)
      if (part_box[q].distance(p.x[i]) < reach && walls.part_distance(q, p.x[i]) < reach) cand[i].push_back(q);
    wall_offset[i + 1] = static_cast<int>(cand[i].size());
  }
  std::partial_sum(wall_offset.begin(), wall_offset.end(), wall_offset.begin());
  wall_part.resize(wall_offset[np]);
  wall_hist.assign(wall_offset[np], contact::History{});
  for (int i = 0; i < no; ++i) {
    std::copy(cand[i].begin(), cand[i].end(), wall_part.begin() + wall_offset[i]);
    if (!have_old) continue;
    const int oi = order[i];
    for (int k = old_woff[oi]; k < old_woff[oi + 1]; ++k)
      for (int e = wall_offset[i]; e < wall_offset[i + 1]; ++e)
        if (wall_part[e] == old_wpart[k]) wall_hist[e] = old_wxi[k];
  }
  for (const CarriedWall& c : incoming.walls) {
    const int i = local_index(by_id, c.id);
    if (i < 0) continue;
    for (int e = wall_offset[i]; e < wall_offset[i + 1]; ++e)
      if (wall_part[e] == c.part) wall_hist[e] = c.h;
  }
  incoming.pairs.clear();
  incoming.walls.clear();

  x_at_build = p.x;
  body_offset_at_build = walls.offset;
}

void NeighborList::retain(const std::vector<int>& keep, size_t n_added) {
  ghosts = 0;
  if (offset.empty()) return;
  const int n_old = static_cast<int>(offset.size()) - 1;
  std::vector<int> new_of_old(n_old, -1);
  for (size_t k = 0; k < keep.size(); ++k) {
    if (keep[k] < 0 || keep[k] >= n_old || (k > 0 && keep[k] <= keep[k - 1]))
      throw Error(fmt::format("neighbour list: kept particle {} is old particle {}, out of range (0..{}) or not "
                              "after the one before",
                              k, keep[k], n_old - 1));
    new_of_old[keep[k]] = static_cast<int>(k);
  }
  const size_t n = keep.size() + n_added;
  // keep increases, so the renumbering keeps the order: each owner's partners stay sorted
  // and above their owner, as build()'s carry-over expects.
  std::vector<int> off(n + 1, 0), pa, woff(n + 1, 0), wpart;
  std::vector<uint8_t> img;
  std::vector<contact::History> xi, wxi;
  for (size_t k = 0; k < keep.size(); ++k) {
    const int i = keep[k];
    for (int e = offset[i]; e < offset[i + 1]; ++e) {
      const int j = new_of_old[partner[e]];
      if (j < 0) continue;
      pa.push_back(j);
      img.push_back(image[e]);
      xi.push_back(hist[e]);
    }
    off[k + 1] = static_cast<int>(pa.size());
    wpart.insert(wpart.end(), wall_part.begin() + wall_offset[i], wall_part.begin() + wall_offset[i + 1]);
    wxi.insert(wxi.end(), wall_hist.begin() + wall_offset[i], wall_hist.begin() + wall_offset[i + 1]);
    woff[k + 1] = static_cast<int>(wpart.size());
  }
  for (size_t k = keep.size(); k < n; ++k) {
    off[k + 1] = off[k];
    woff[k + 1] = woff[k];
  }
  offset.swap(off);
  partner.swap(pa);
  image.swap(img);
  hist.swap(xi);
  wall_offset.swap(woff);
  wall_part.swap(wpart);
  wall_hist.swap(wxi);
  // Derived state of the old numbering: dropped rather than left describing other
  // particles; the next build() recomputes it.
  for (auto* v : {&rev_offset, &rev_entry, &rev_pos, &first_owner, &last_owner}) v->clear();
  live.clear();
  direct.clear();
  f_partner.clear();
  t_partner.clear();
  f_acc.clear();
  t_acc.clear();
  direct_team = 0;
  x_at_build.clear();  // needs_rebuild() is true until the next build()
}

void NeighborList::derive() {
  const size_t ne = partner.size();
  live.resize(ne);
  for (size_t e = 0; e < ne; ++e) live[e] = !hist[e].empty();
  rev_pos.resize(ne);
  for (size_t k = 0; k < rev_entry.size(); ++k) {
    if (rev_entry[k] < 0 || static_cast<size_t>(rev_entry[k]) >= ne)
      throw Error("neighbour list: reverse index out of range (corrupt checkpoint?)");
    rev_pos[rev_entry[k]] = static_cast<int>(k);
  }
  f_partner.assign(ne, Vec3{});
  t_partner.assign(ne, Vec3{});
  const int np = static_cast<int>(offset.size()) - 1;
  first_owner.assign(np, -1);
  last_owner.assign(np, -1);
  for (int i = 0; i < np; ++i)
    for (int e = offset[i]; e < offset[i + 1]; ++e) {
      const int j = partner[e];
      if (first_owner[j] < 0) first_owner[j] = i;
      last_owner[j] = i;
    }
  f_acc.assign(np, Vec3{});
  t_acc.assign(np, Vec3{});
  direct_team = 0;
}

bool NeighborList::needs_rebuild(double max_move2, size_t n, const geometry::Scene::Frame& walls) const {
  if (x_at_build.size() != n) return true;
  double wall_move = 0;
  for (size_t b = 0; b < walls.offset.size() && b < body_offset_at_build.size(); ++b)
    wall_move = std::max(wall_move, norm(walls.offset[b] - body_offset_at_build[b]));
  const double wall_limit = 0.5 * skin - wall_move;
  if (wall_limit <= 0) return true;
  // As below: some particle moved more than skin/2, or more than the wall limit.
  return max_move2 > 0.25 * skin * skin || max_move2 > wall_limit * wall_limit;
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
