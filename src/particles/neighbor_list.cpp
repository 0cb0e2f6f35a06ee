// NeighborList (neighbor_list.hpp) apart from build() (neighbor_build.cpp): following a
// change of the particle set, the derived fields, the rebuild test.
#include "particles/neighbor_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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

void NeighborList::set_accounts(bool on) {
  if (hist.accounts == on && spare.hist.accounts == on) return;
  hist.clear();
  spare.hist.clear();
  hist.accounts = spare.hist.accounts = on;
  offset.clear();  // no lists: the next step builds them (their histories were dropped)
  x_at_build.clear();
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
  contact::HistoryStore xi;
  xi.accounts = hist.accounts;
  std::vector<contact::History> wxi;
  for (size_t k = 0; k < keep.size(); ++k) {
    const int i = keep[k];
    for (int e = offset[i]; e < offset[i + 1]; ++e) {
      const int j = new_of_old[partner[e]];
      if (j < 0) continue;
      pa.push_back(j);
      img.push_back(image[e]);
      xi.push_back(hist.get(e));
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

// Every loop writes each element once, from its own inputs: parallel, and the same result
// for any number of threads.
void NeighborList::derive() {
  const long ne = static_cast<long>(partner.size()), nr = static_cast<long>(rev_entry.size());
  const int np = static_cast<int>(offset.size()) - 1;
  const bool par = ne >= 4096;
  // The loops below index by partner and by the entries' places in the reverse index.
  long bad = np < 0 || rev_offset.size() != static_cast<size_t>(np) + 1 || rev_offset.front() != 0 ||
             rev_offset.back() != nr || nr != ne || offset.front() != 0 || offset.back() != ne;
  for (int j = 0; j < np && !bad; ++j) bad = rev_offset[j + 1] < rev_offset[j] || offset[j + 1] < offset[j];
  if (!bad) {  // (nr = ne: partner[k] is read within its bounds)
#pragma omp parallel for schedule(static) if (par) reduction(+ : bad)
    for (long k = 0; k < nr; ++k) bad += rev_entry[k] < 0 || rev_entry[k] >= ne || partner[k] < 0 || partner[k] >= np;
  }
  if (bad) throw Error("neighbour list: entries or reverse index out of range (corrupt checkpoint?)");
  live.resize(ne);
  rev_pos.resize(ne);
  f_partner.resize(ne);
  t_partner.resize(ne);
  first_owner.resize(np);
  last_owner.resize(np);
  f_acc.resize(np);
  t_acc.resize(np);
  // rev_pos first; then each partner's lowest and highest owners: the owners of its first
  // and last entries (the reverse index lists them in increasing entry order, and entries
  // go owner by owner). Exactly one entry is a partner's first, one its last.
  long dup = 0;
#pragma omp parallel if (par) reduction(+ : dup)
  {
#pragma omp for schedule(static) nowait
    for (long e = 0; e < ne; ++e) live[e] = !hist.empty(e);
#pragma omp for schedule(static) nowait
    for (long e = 0; e < ne; ++e) rev_pos[e] = -1;
#pragma omp for schedule(static)
    for (int j = 0; j < np; ++j) {
      first_owner[j] = last_owner[j] = -1;
      f_acc[j] = Vec3{};
      t_acc[j] = Vec3{};
    }
#pragma omp for schedule(static)
    for (long k = 0; k < nr; ++k) rev_pos[rev_entry[k]] = static_cast<int>(k);
#pragma omp for schedule(static)
    for (int i = 0; i < np; ++i)
      for (int e = offset[i]; e < offset[i + 1]; ++e) {
        const int j = partner[e], k = rev_pos[e];
        dup += k < rev_offset[j] || k >= rev_offset[j + 1];  // also k = -1: e not in the index
        if (k == rev_offset[j]) first_owner[j] = i;
        if (k == rev_offset[j + 1] - 1) last_owner[j] = i;
      }
  }
  if (dup) throw Error("neighbour list: the reverse index does not list each entry once under its partner (corrupt "
                       "checkpoint?)");
  direct_team = 0;
}

bool NeighborList::needs_rebuild(const MoveBounds& moved, size_t n, const geometry::Scene::Frame& walls,
                                 bool relative) const {
  if (x_at_build.size() != n) return true;
  // Each particle's own displacement, as below: some particle moved more than skin/2, or
  // more than the wall limit. Enough for the lists to be complete; with `relative` the
  // other test may find them complete still (either suffices).
  double wall_move = 0;
  for (size_t b = 0; b < walls.offset.size() && b < body_offset_at_build.size(); ++b)
    wall_move = std::max(wall_move, norm(walls.offset[b] - body_offset_at_build[b]));
  const double wall_limit = 0.5 * skin - wall_move;
  const bool each = wall_limit > 0 && !(moved.max2 > 0.25 * skin * skin || moved.max2 > wall_limit * wall_limit);
  if (each || !relative) return !each;
  if (body_offset_at_build.size() != walls.offset.size()) return true;
  if (!(moved.lo.x <= moved.hi.x && moved.lo.y <= moved.hi.y && moved.lo.z <= moved.hi.z)) return false;  // none
  // Pairs (neighbor_list.hpp): twice the half-diagonal of the displacements' box below skin.
  const Vec3 half = 0.5 * (moved.hi - moved.lo);
  if (4.0 * norm2(half) >= skin * skin) return true;
  // Walls: every body (the static ones have dw = 0) against the box of displacements.
  for (size_t b = 0; b < walls.offset.size(); ++b) {
    const Vec3 dw = walls.offset[b] - body_offset_at_build[b];
    Vec3 e;
    for (int a = 0; a < 3; ++a) e[a] = std::max(moved.hi[a] - dw[a], dw[a] - moved.lo[a]);
    if (norm2(e) >= skin * skin) return true;
  }
  return false;
}

MoveBounds NeighborList::moved_since_build(const Particles& p) const {
  MoveBounds m;
  const int np = static_cast<int>(std::min(p.size(), x_at_build.size()));
  double max2 = 0, lo[3] = {m.lo.x, m.lo.y, m.lo.z}, hi[3] = {m.hi.x, m.hi.y, m.hi.z};
#pragma omp parallel for schedule(static) reduction(max : max2, hi[:3]) reduction(min : lo[:3]) if (np >= 512)
  for (int i = 0; i < np; ++i) {
    const Vec3 d = p.x[i] - x_at_build[i];
    const double d2 = norm2(d);
    max2 = d2 > max2 ? d2 : max2;  // a NaN compares false and is passed over
    for (int a = 0; a < 3; ++a) lo[a] = d[a] < lo[a] ? d[a] : lo[a], hi[a] = d[a] > hi[a] ? d[a] : hi[a];
  }
  m.max2 = max2;
  m.lo = {lo[0], lo[1], lo[2]};
  m.hi = {hi[0], hi[1], hi[2]};
  return m;
}

bool NeighborList::needs_rebuild(const Particles& p, const geometry::Scene::Frame& walls) const {
  return needs_rebuild(moved_since_build(p), p.size(), walls, false);
}

}  // namespace cgdem
