// NeighborList::build (neighbor_list.hpp) and its steps: the cell grid, the sort of the
// particles along it, the half pair lists with their histories carried over, the reverse
// index and the wall candidates.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "particles/neighbor_list.hpp"

namespace cgdem {

namespace {

// Cells are numbered along the axes fast[0] (fastest), fast[1], fast[2] (slowest): the axis
// with the most cells is the slowest, so that the particles of the cells around a particle
// (after the sort by cell) lie within n[fast[0]] x n[fast[1]] cells of it in memory.
struct CellGrid {
  Vec3 lo;
  double h[3] = {1, 1, 1};
  int n[3] = {1, 1, 1};
  int fast[3] = {0, 1, 2};
  void coords(const Vec3& x, int c[3]) const {
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((x[a] - lo[a]) / h[a]), 0, n[a] - 1);
  }
  // The index of the cell at a, b, c along fast[0], fast[1], fast[2].
  long index_along(int a, int b, int c) const {
    return a + static_cast<long>(n[fast[0]]) * (b + static_cast<long>(n[fast[1]]) * c);
  }
  long index(const int c[3]) const { return index_along(c[fast[0]], c[fast[1]], c[fast[2]]); }
};

constexpr int kNoImage = 13;  // image code (sx+1) + 3 (sy+1) + 9 (sz+1) with s = 0

// The entry of pair (owner, other), owner < other, or -1: pair lists are sorted by partner.
int find_entry(const std::vector<int>& off, const std::vector<int>& partner, int owner, int other) {
  auto first = partner.begin() + off[owner], last = partner.begin() + off[owner + 1];
  auto it = std::lower_bound(first, last, other);
  return it == last || *it != other ? -1 : static_cast<int>(it - partner.begin());
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


// The build's steps (NeighborList::build below). Each says what it reads and writes;
// none depends on the number of threads: a parallel loop writes per-particle results
// only, and everything is in a fixed order (cells, then index).

// Reads ghosts, periodic; throws when the ghosts cannot be handled.
void check_ghosts(const NeighborList& nl, const Particles& p) {
  if (nl.ghosts > p.size())
    throw Error(fmt::format("neighbour list: {} ghosts among {} particles", nl.ghosts, p.size()));
  if (nl.ghosts > 0 && nl.periodic.any())
    throw Error("neighbour list: ghost parcels on periodic axes are not supported (their periodic images would be "
                "missing)");
}

// Cell grid over the particles' bounding box (the period on periodic axes), cells at least
// one interaction range (largest diameter plus skin) wide. Ghosts are in the box: pairs
// with them are found through the same grid. Reads x, radius; writes nl.shift (the 27
// image shifts). Throws when a periodic length holds fewer than three cells.
CellGrid make_cell_grid(NeighborList& nl, const Particles& p) {
  const int np = static_cast<int>(p.size());
  const Periodicity& periodic = nl.periodic;
  CellGrid g;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
  double rmax = 0;
  for (int i = 0; i < np; ++i) {
    lo = cmin(lo, p.x[i]);
    hi = cmax(hi, p.x[i]);
    rmax = std::max(rmax, p.radius[i]);
  }
  if (np == 0) lo = hi = Vec3{};
  double range = 2 * rmax + nl.skin;
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
  // Fewest cells fastest (ties in x, y, z order).
  std::stable_sort(g.fast, g.fast + 3, [&g](int a, int b) { return g.n[a] < g.n[b]; });
  for (int c = 0; c < 27; ++c) {
    const int s[3] = {c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1};
    for (int a = 0; a < 3; ++a) nl.shift[c][a] = periodic.axis[a] ? s[a] * (periodic.hi[a] - periodic.lo[a]) : 0.0;
  }
  return g;
}

// The particles by cell: the owned ones 0..no-1 sorted (order[new] = old, cells in index
// order, a cell's particles in index order), the ghosts no..np-1 in their places (order is
// the identity on them: the halo exchange fills them in the order it appended them), with
// a cell index of their own: ghost_in[ghost_start[c] .. ghost_start[c+1]-1] are the ghosts
// in cell c. start[c] .. start[c+1]-1 are the owned particles of cell c after the sort.
struct CellOrder {
  std::vector<int> order, start, ghost_start, ghost_in;
};

// Reads x; writes the CellOrder and reorders p by it.
CellOrder sort_by_cell(Particles& p, const CellGrid& g, int no, Particles::ReorderScratch& scratch) {
  const int np = static_cast<int>(p.size());
  const long ncell = static_cast<long>(g.n[0]) * g.n[1] * g.n[2];
  CellOrder s;
  std::vector<long> cell(np);
  s.start.assign(ncell + 1, 0);
  for (int i = 0; i < no; ++i) {
    int c[3];
    g.coords(p.x[i], c);
    ++s.start[(cell[i] = g.index(c)) + 1];
  }
  std::partial_sum(s.start.begin(), s.start.end(), s.start.begin());
  s.order.resize(np);
  std::vector<int> fill(s.start.begin(), s.start.end() - 1);
  for (int i = 0; i < no; ++i) s.order[fill[cell[i]]++] = i;
  for (int i = no; i < np; ++i) s.order[i] = i;
  if (no < np) {
    s.ghost_start.assign(ncell + 1, 0);
    for (int i = no; i < np; ++i) {
      int c[3];
      g.coords(p.x[i], c);
      ++s.ghost_start[(cell[i] = g.index(c)) + 1];
    }
    std::partial_sum(s.ghost_start.begin(), s.ghost_start.end(), s.ghost_start.begin());
    s.ghost_in.resize(np - no);
    std::vector<int> gfill(s.ghost_start.begin(), s.ghost_start.end() - 1);
    for (int i = no; i < np; ++i) s.ghost_in[gfill[cell[i]]++] = i;
  }
  p.reorder(s.order, scratch);
  return s;
}

// The lists of the last build, in its (old) particle indices, for the history carry-over.
struct OldLists {
  std::vector<int> off, partner, woff, wpart;
  contact::HistoryStore hist;
  std::vector<contact::History> whist;
  bool valid = false;  // the old lists cover the same particles
};

// The arrays that a build rebuilds, each with its place in the old lists and in nl.spare:
// f(old, current, spare) for each of them.
template <class F>
void for_each_rebuilt(OldLists& o, NeighborList& nl, F&& f) {
  f(o.off, nl.offset, nl.spare.offset);
  f(o.partner, nl.partner, nl.spare.partner);
  f(o.hist, nl.hist, nl.spare.hist);
  f(o.woff, nl.wall_offset, nl.spare.wall_offset);
  f(o.wpart, nl.wall_part, nl.spare.wall_part);
  f(o.whist, nl.wall_hist, nl.spare.wall_hist);
}

// Moves offset, partner, hist and the wall lists out of nl (they are rebuilt into the
// storage of nl.spare, whose contents are stale).
OldLists take_lists(NeighborList& nl, int np) {
  OldLists o;
  for_each_rebuilt(o, nl, [](auto& old, auto& current, auto& spare) {
    old.swap(current);
    current.swap(spare);
  });
  o.valid = o.off.size() == static_cast<size_t>(np) + 1;
  return o;
}

// Keeps the old lists' storage in nl.spare for the next build.
void keep_as_spare(NeighborList& nl, OldLists& o) {
  for_each_rebuilt(o, nl, [](auto& old, auto&, auto& spare) { spare.swap(old); });
}

// The 27 cells around owned particle i: appends (j, image code) to `out` for every partner j
// within reach (r_i + r_j + skin), owned partners of higher index and the ghosts (all above
// i). Ghosts own no entries. The order of the pairs is not the lists' order: find_pairs sorts
// each owner's pairs.
struct PairSearch {
  const Particles& p;
  const CellGrid& g;
  const CellOrder& cells;
  const NeighborList& nl;
  int no, np;

  using Found = std::vector<std::pair<int, int>>;

  void neighbours(int i, Found& out) const {
    const Vec3& x0 = p.x[i];
    int c[3];
    g.coords(x0, c);
    const int fa = g.fast[0], fb = g.fast[1], fc = g.fast[2];  // fastest .. slowest axis
    // A row of up to three cells along the fastest axis that needs no periodic image holds
    // consecutive cell indices, so its owned particles are one range of the sorted order.
    const bool row_unwrapped = !nl.periodic.axis[fa] || (c[fa] >= 1 && c[fa] <= g.n[fa] - 2);
    const int ra = std::max(c[fa] - 1, 0), rb = std::min(c[fa] + 1, g.n[fa] - 1);
    int cell[3], img[3];  // the visited cell and its image along each axis (-1, 0, 1)
    auto code = [&img] { return (img[0] + 1) + 3 * (img[1] + 1) + 9 * (img[2] + 1); };
    for (int dc = -1; dc <= 1; ++dc) {
      cell[fc] = c[fc] + dc, img[fc] = 0;
      if (!wrap(fc, cell[fc], img[fc])) continue;
      for (int db = -1; db <= 1; ++db) {
        cell[fb] = c[fb] + db, img[fb] = 0;
        if (!wrap(fb, cell[fb], img[fb])) continue;
        if (row_unwrapped) {
          img[fa] = 0;
          const int k = code();
          owned(i, x0, cells.start[g.index_along(ra, cell[fb], cell[fc])],
                cells.start[g.index_along(rb, cell[fb], cell[fc]) + 1], k, out);
          if (no < np)
            for (int r = ra; r <= rb; ++r) ghosts(i, x0, g.index_along(r, cell[fb], cell[fc]), k, out);
          continue;
        }
        for (int da = -1; da <= 1; ++da) {
          cell[fa] = c[fa] + da, img[fa] = 0;
          if (!wrap(fa, cell[fa], img[fa])) continue;
          const int k = code();
          const long cc = g.index(cell);
          owned(i, x0, cells.start[cc], cells.start[cc + 1], k, out);
          if (no < np) ghosts(i, x0, cc, k, out);
        }
      }
    }
  }

 private:
  // Cell coordinate c along axis a, wrapped on a periodic axis (s: the image, -1, 0, 1);
  // false when it lies outside a non-periodic grid.
  bool wrap(int a, int& c, int& s) const {
    if (c >= 0 && c < g.n[a]) return true;
    if (!nl.periodic.axis[a]) return false;
    s = c < 0 ? -1 : 1;
    c -= s * g.n[a];
    return true;
  }
  // The owned particles ja .. jb - 1 of the sorted order, those above i. Without a branch
  // per candidate (about one in five is within reach, in no pattern): each is written at
  // the end of `out`, which advances past it when it is within reach. The arrays' pointers
  // are read once (writes to `out` could otherwise alias them).
  void owned(int i, const Vec3& x0, int ja, int jb, int code, Found& out) const {
    const int j0 = std::max(ja, i + 1);
    if (j0 >= jb) return;
    const size_t n0 = out.size();
    out.resize(n0 + static_cast<size_t>(jb - j0));
    std::pair<int, int>* o = out.data() + n0;
    const Vec3* x = p.x.data();
    const double* radius = p.radius.data();
    const Vec3 shift = nl.shift[code];
    const double ri = radius[i], skin = nl.skin;
    size_t n = 0;
    for (int j = j0; j < jb; ++j) {
      const double reach = ri + radius[j] + skin;
      o[n] = {j, code};
      n += norm2(x[j] + shift - x0) < reach * reach;
    }
    out.resize(n0 + n);
  }
  // The ghosts in cell cc.
  void ghosts(int i, const Vec3& x0, long cc, int code, Found& out) const {
    for (int k = cells.ghost_start[cc]; k < cells.ghost_start[cc + 1]; ++k) {
      const int j = cells.ghost_in[k];
      const double reach = p.radius[i] + p.radius[j] + nl.skin;
      if (norm2(p.x[j] + nl.shift[code] - x0) < reach * reach) out.emplace_back(j, code);
    }
  }
};

// The history of the pair of old indices oi, oj in the old lists, in the frame of oi
// (empty when the pair was not listed).
contact::History carried_history(const OldLists& old, int oi, int oj) {
  const int e = find_entry(old.off, old.partner, std::min(oi, oj), std::max(oi, oj));
  if (e < 0) return contact::History{};
  const contact::History h = old.hist.get(e);
  return oi < oj ? h : h.flipped();
}

// Half pair lists: reads the PairSearch; writes offset (count, then prefix sum), partner
// (each owner's partners in increasing index), image, and hist: the history of the same
// pair in the old lists, by old indices, stored under the lower of the two and flipped
// when the owner changed. One search per owner: each thread collects the pairs of its
// block of owners (the same static blocks in both loops), into storage kept between builds
// (nl.spare.found), then copies them to their places once the prefix sum gives the
// offsets; every entry is written by one thread.
void find_pairs(NeighborList& nl, const PairSearch& s, const std::vector<int>& order, const OldLists& old) {
  const int np = s.np, no = s.no;
  nl.offset.assign(np + 1, 0);
#pragma omp parallel if (np >= 512)
  {
#pragma omp single
    if (nl.spare.found.size() < static_cast<size_t>(omp_get_num_threads()))
      nl.spare.found.resize(omp_get_num_threads());
    // (implicit barrier)
    // (partner, image code), owner after owner. A local vector: the threads' vector headers
    // lie side by side in nl.spare.found, and pushing through them would share a cache line.
    std::vector<std::pair<int, int>> found;
    found.swap(nl.spare.found[omp_get_thread_num()]);
    found.clear();
#pragma omp for schedule(static)
    for (int i = 0; i < no; ++i) {
      const size_t first = found.size();
      s.neighbours(i, found);
      std::sort(found.begin() + static_cast<long>(first), found.end());
      nl.offset[i + 1] = static_cast<int>(found.size() - first);
    }
#pragma omp single
    {
      std::partial_sum(nl.offset.begin(), nl.offset.end(), nl.offset.begin());
      const int ne = nl.offset[np];
      nl.partner.resize(ne);
      nl.image.resize(ne);
      nl.hist.resize(ne);  // stale storage (nl.spare): every entry is written below
    }  // (implicit barrier: the offsets and sizes are set for every thread)
    size_t k = 0;
#pragma omp for schedule(static)
    for (int i = 0; i < no; ++i)
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e, ++k) {
        nl.partner[e] = found[k].first;
        nl.image[e] = static_cast<uint8_t>(found[k].second);
        nl.hist.set(e, old.valid ? carried_history(old, order[i], order[found[k].first]) : contact::History{});
      }
    found.swap(nl.spare.found[omp_get_thread_num()]);  // kept for the next build
  }
}

// Histories carried in from other ranks (nl.incoming.pairs): each attached to its pair by
// particle id, flipped when the owner (the lower index) is id_b. Writes hist.
void attach_incoming_pairs(NeighborList& nl, const std::vector<std::pair<int64_t, int>>& by_id) {
  for (const CarriedPair& c : nl.incoming.pairs) {
    const int a = local_index(by_id, c.id_a), b = local_index(by_id, c.id_b);
    if (a < 0 || b < 0 || a == b) continue;
    const int e = find_entry(nl.offset, nl.partner, std::min(a, b), std::max(a, b));
    if (e >= 0) nl.hist.set(e, a < b ? c.h : c.h.flipped());
  }
}

// Reads partner; writes rev_offset, rev_entry: for each partner its entries in increasing order.
void build_reverse_index(NeighborList& nl, int np) {
  const int ne = static_cast<int>(nl.partner.size());
  nl.rev_offset.assign(np + 1, 0);
  for (int e = 0; e < ne; ++e) ++nl.rev_offset[nl.partner[e] + 1];
  std::partial_sum(nl.rev_offset.begin(), nl.rev_offset.end(), nl.rev_offset.begin());
  nl.rev_entry.resize(ne);
  std::vector<int> pos(nl.rev_offset.begin(), nl.rev_offset.end() - 1);
  for (int e = 0; e < ne; ++e) nl.rev_entry[pos[nl.partner[e]]++] = e;
}

// Wall candidates of the owned particles (a ghost's wall contacts are its owner's): the
// parts whose surface lies within r + skin, in part order. Reads x, radius, the wall
// frame; writes wall_offset, wall_part, and wall_hist carried over from the old lists by
// old index and part, then from nl.incoming.walls by id. Parallel over particles, each
// writing its own candidates.
void find_wall_candidates(NeighborList& nl, const Particles& p, const geometry::Scene::Frame& walls, int no,
                          const std::vector<int>& order, const OldLists& old,
                          const std::vector<std::pair<int64_t, int>>& by_id) {
  const int np = static_cast<int>(p.size());
  const int nparts = static_cast<int>(walls.scene ? walls.scene->parts().size() : 0);
  std::vector<geometry::Aabb> part_box(nparts);
  for (int q = 0; q < nparts; ++q) part_box[q] = walls.part_bounds(q);
  nl.wall_offset.assign(np + 1, 0);
  auto is_candidate = [&](int i, int q) {
    const double reach = p.radius[i] + nl.skin;
    return part_box[q].distance(p.x[i]) < reach && walls.part_distance(q, p.x[i]) < reach;
  };
  // Up to 64 parts: each particle's candidates as a bit mask (bit q: part q), no
  // allocation per particle; more parts: a list per particle.
  const bool masks = nparts <= 64;
  std::vector<uint64_t> mask(masks ? np : 0);
  std::vector<std::vector<int>> cand(masks ? 0 : np);
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < no; ++i) {
    if (masks) {
      uint64_t m = 0;
      for (int q = 0; q < nparts; ++q)
        if (is_candidate(i, q)) m |= uint64_t{1} << q;
      mask[i] = m;
      nl.wall_offset[i + 1] = std::popcount(m);
    } else {
      for (int q = 0; q < nparts; ++q)
        if (is_candidate(i, q)) cand[i].push_back(q);
      nl.wall_offset[i + 1] = static_cast<int>(cand[i].size());
    }
  }
  std::partial_sum(nl.wall_offset.begin(), nl.wall_offset.end(), nl.wall_offset.begin());
  nl.wall_part.resize(nl.wall_offset[np]);
  nl.wall_hist.resize(nl.wall_offset[np]);
  // Each particle writes its own entries: its parts in part order, their histories (the
  // old lists' for the same part, else none).
#pragma omp parallel for schedule(static) if (np >= 512)
  for (int i = 0; i < no; ++i) {
    int e = nl.wall_offset[i];
    if (masks) {
      for (uint64_t m = mask[i]; m; m &= m - 1) nl.wall_part[e++] = std::countr_zero(m);
    } else {
      std::copy(cand[i].begin(), cand[i].end(), nl.wall_part.begin() + e);
    }
    for (e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) nl.wall_hist[e] = contact::History{};
    if (!old.valid) continue;
    const int oi = order[i];
    for (int k = old.woff[oi]; k < old.woff[oi + 1]; ++k)
      for (e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
        if (nl.wall_part[e] == old.wpart[k]) nl.wall_hist[e] = old.whist[k];
  }
  for (const CarriedWall& c : nl.incoming.walls) {
    const int i = local_index(by_id, c.id);
    if (i < 0) continue;
    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
      if (nl.wall_part[e] == c.part) nl.wall_hist[e] = c.h;
  }
}

}  // namespace

// The build, step by step (each step's contract is at its definition above). The order of
// the particles, of the entries and of the histories depends on the positions only, not
// on the number of threads.
void NeighborList::build(Particles& p, const geometry::Scene::Frame& walls) {
  check_ghosts(*this, p);
  const int np = static_cast<int>(p.size());
  const int no = np - static_cast<int>(ghosts);  // owned particles 0..no-1, ghosts no..np-1
  ++builds;
  if (periodic.any())
    for (int i = 0; i < np; ++i) periodic.wrap(p.x[i]);
  const CellGrid grid = make_cell_grid(*this, p);
  const CellOrder cells = sort_by_cell(p, grid, no, spare.sort);
  OldLists old = take_lists(*this, np);
  find_pairs(*this, PairSearch{p, grid, cells, *this, no, np}, cells.order, old);
  std::vector<std::pair<int64_t, int>> by_id;  // an empty `incoming` costs nothing
  if (!incoming.empty()) by_id = index_by_id(p.id);
  attach_incoming_pairs(*this, by_id);
  build_reverse_index(*this, np);
  derive();
  find_wall_candidates(*this, p, walls, no, cells.order, old, by_id);
  incoming.pairs.clear();
  incoming.walls.clear();
  x_at_build = p.x;
  body_offset_at_build = walls.offset;
  keep_as_spare(*this, old);
}

}  // namespace cgdem
