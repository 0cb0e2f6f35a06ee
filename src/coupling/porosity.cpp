// Porosity next to walls: the kernel capacity of the cells and the porosity of the packing
// (exchange.hpp, "Porosity next to walls"; docs/coupling.md).
//
//   C_r(j) = (1/dx^3) Int_{phi(x) >= r} w~_j(x) dx                          (capacity)
//   eps(j) = max(eps_min, 1 - sum_r V_s,r(j) / (C_r(j) dx^3))                (porosity)
//
// w~_j is the parcels' own masked cell weight of node j (kernel.hpp), phi the walls' signed
// distance (eq. 15) and r the radius of a parcel: the integral runs over every place a
// parcel's centre can reach. A packing of solid fraction phi_s that fills those places
// deposits V_s(j) = phi_s C(j) dx^3, so eps(j) = 1 - phi_s is the packing's own porosity
// in every cell, whatever the walls cut off the cell and however the mask moved the kernel.
// C = 1 exactly wherever neither a wall (alpha > 0 within the kernel's reach, or a place
// closer than r to a wall) nor a domain end (whose nodes the kernel folds back) is near.
//
// Quadrature: each cell is split into 3 x 3 x 3 sub-cubes, each a pseudo-parcel of its
// reachable volume at its reachable centroid (where phi = r crosses a sub-cube, both from
// phi's linear approximation there, exact for plane walls), deposited with the parcels'
// masked weights. Away from walls the 27 sub-cube centres of a cell are a lattice of
// spacing dx/3, on which the TSC weights sum to the exact integral (the spline's transform
// vanishes at the multiples of 3/dx): the cells of a node's neighbourhood with no wall near
// ("plain" cells) deposit the exact tabulated values, and C = 1 is reproduced to round-off
// in the limit of no walls.
#include <algorithm>
#include <cmath>

#include "coupling/exchange.hpp"

namespace cgdem::coupling {

namespace {

constexpr int kSub = 3;  // sub-cubes per axis of a cell
constexpr int kCol = 4;  // columns per axis of a sub-cube that a wall cuts

// Sum over the 3 sub-cube centres of a cell at offset o (-1, 0, 1 from the node) of the
// 1D TSC weight of the node, divided by 3: the quadrature's share of the node's integral
// that one plain cell contributes along one axis.
std::array<double, 3> plain_shares() {
  std::array<double, 3> s{};
  for (int o = -1; o <= 1; ++o) {
    double sum = 0;
    for (int q = 0; q < kSub; ++q) {
      const double t = o + (q + 0.5) / kSub - 0.5;  // sub-cube centre relative to the node [dx]
      const double a = std::fabs(t);
      sum += a <= 0.5 ? 0.75 - t * t : (a < 1.5 ? 0.5 * (1.5 - a) * (1.5 - a) : 0.0);
    }
    s[o + 1] = sum / kSub;
  }
  return s;
}

}  // namespace

// Cells near a wall: those within `reach` cells (box distance) of a cell with alpha > 0,
// over the block and its ghost layers (reads clamped to the ghost layers' extent).
std::vector<unsigned char> Exchange::near_walls(int reach) const {
  const std::array<int, 3> n = g_.n();
  const int gh = fluid::kGhost;
  const std::array<int, 3> e{n[0] + 2 * gh, n[1] + 2 * gh, n[2] + 2 * gh};
  const size_t total = static_cast<size_t>(e[0]) * e[1] * e[2];
  std::vector<unsigned char> m(total, 0), t(total, 0);
  if (!(walls_ && walls_->valid && walls_->any_solid)) return m;
  const fluid::Field& al = walls_->alpha_cell;  // its layout is cell_layout_'s: index = padded offset
#pragma omp parallel for schedule(static) if (static_cast<long>(total) > fluid::kOmpMinWork)
  for (size_t q = 0; q < total; ++q) m[q] = al.data()[q] > 0;
  const std::array<long, 3> st{1, e[0], static_cast<long>(e[0]) * e[1]};
  // Separable dilation, one axis at a time (each t from m alone): a row of t is the OR of
  // the rows of m shifted by -reach..reach along the axis (those that exist), in whole-row
  // loops that vectorize.
  for (int d = 0; d < 3; ++d) {
#pragma omp parallel for schedule(static) if (static_cast<long>(total) > fluid::kOmpMinWork)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j) {
        const long o = st[1] * j + st[2] * k;
        unsigned char* tr = t.data() + o;
        const unsigned char* mr = m.data() + o;
        std::fill(tr, tr + e[0], static_cast<unsigned char>(0));
        const int q = d == 0 ? 0 : (d == 1 ? j : k);
        for (int s = -reach; s <= reach; ++s) {
          if (d == 0) {
            const int lo = std::max(0, -s), hi = std::min(e[0], e[0] - s);
            for (int i = lo; i < hi; ++i) tr[i] |= mr[i + s];
          } else if (q + s >= 0 && q + s < e[d]) {
            const unsigned char* src = mr + s * st[d];
            for (int i = 0; i < e[0]; ++i) tr[i] |= src[i];
          }
        }
      }
    m.swap(t);
  }
  return m;
}

bool Exchange::plain_cell(int i, int j, int k, const std::vector<unsigned char>& near) const {
  const std::array<int, 3> q{i, j, k}, n = g_.n();
  for (int a = 0; a < 3; ++a)  // the kernel folds back the nodes beyond a domain end
    if (!periodic_[a] && ((q[a] <= 0 && !cells_.ghost_side[2 * a]) || (q[a] >= n[a] - 1 && !cells_.ghost_side[2 * a + 1])))
      return false;
  return !near[cell_layout_.index(i, j, k)];
}

// The part of the sub-cube of side h centred at c where phi >= r, from phi's linear
// approximation there (exact for a plane wall): its volume fraction and its centroid, by
// kCol x kCol columns along the axis phi changes fastest on, each cut exactly. False when
// nothing of it is reachable.
bool Exchange::reachable_part(const Vec3& c, double h, double r, double& frac, Vec3& centroid) const {
  const double pc = frame_->phi(c), hd = 0.5 * std::sqrt(3.0) * h;
  if (pc >= r + hd) return frac = 1, centroid = c, true;
  if (pc <= r - hd) return false;
  const double dl = 1e-3 * h;
  Vec3 grad;
  for (int e = 0; e < 3; ++e) {
    Vec3 dv{};
    dv[e] = dl;
    grad[e] = (frame_->phi(c + dv) - frame_->phi(c - dv)) / (2 * dl);
  }
  // the first axis within 1e-6 of the steepest: ties (a wall's edge or corner on the
  // sub-cube's diagonal) do not depend on the round-off of a block's coordinates
  const double gmax = std::max({std::fabs(grad[0]), std::fabs(grad[1]), std::fabs(grad[2])});
  int a = 0;
  while (std::fabs(grad[a]) < gmax - 1e-6) ++a;
  if (!(std::fabs(grad[a]) > 1e-9)) {  // phi flat here (a ridge): the centre decides
    if (pc < r) return false;
    return frac = 1, centroid = c, true;
  }
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  double len = 0;
  Vec3 moment{};
  for (int q = 0; q < kCol; ++q)
    for (int p = 0; p < kCol; ++p) {
      const double yu = ((p + 0.5) / kCol - 0.5) * h, yv = ((q + 0.5) / kCol - 0.5) * h;
      // pc + grad_a t + grad_u yu + grad_v yv >= r along the column, t in [-h/2, h/2]
      const double t0 = (r - pc - grad[u] * yu - grad[v] * yv) / grad[a];
      double lo = -0.5 * h, hi = 0.5 * h;
      if (grad[a] > 0) lo = std::max(lo, t0); else hi = std::min(hi, t0);
      if (!(hi > lo)) continue;
      Vec3 x = c;
      x[u] += yu, x[v] += yv, x[a] += 0.5 * (lo + hi);
      len += hi - lo;
      moment += (hi - lo) * x;
    }
  if (!(len > 0)) return false;
  frac = len / (kCol * kCol * h);
  centroid = (1.0 / len) * moment;
  return true;
}

void Exchange::deposit_plain_capacity(int i, int j, int k, fluid::Field& cap) const {
  static const std::array<double, 3> share = plain_shares();
  // the exact tabulated shares (no fold: plain cells lie away from the domain's ends)
  const std::array<int, 3> n = g_.n();
  for (int c = -1; c <= 1; ++c)
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a) {
        std::array<int, 3> m{i + a, j + b, k + c};
        for (int e = 0; e < 3; ++e)
          if (periodic_[e]) m[e] = (m[e] % n[e] + n[e]) % n[e];
        // node m receives from cell (i,j,k) at offset (cell - node) = -(a, b, c)
        cap(m[0], m[1], m[2]) += share[1 - a] * share[1 - b] * share[1 - c];
      }
}

int Exchange::cell_capacity_items(int i, int j, int k, double r, CapacityItem* out) const {
  const double h = g_.dx / kSub, half_diag = 0.5 * std::sqrt(3.0) * g_.dx;
  const Vec3 lo = g_.cell_centre(i, j, k) - 0.5 * g_.dx * Vec3{1, 1, 1};
  const bool walls = frame_ && frame_->scene && !frame_->scene->empty();
  const double pc = walls ? frame_->phi(g_.cell_centre(i, j, k)) : INFINITY;
  if (pc <= r - half_diag) return 0;  // no centre can be anywhere in the cell
  const bool all_in = pc >= r + half_diag;
  int n = 0;
  for (int c = 0; c < kSub; ++c)
    for (int b = 0; b < kSub; ++b)
      for (int a = 0; a < kSub; ++a) {
        const Vec3 s0 = lo + h * Vec3{double(a), double(b), double(c)};
        double frac = 1;
        Vec3 centroid = s0 + 0.5 * h * Vec3{1, 1, 1};
        if (!all_in && !reachable_part(centroid, h, r, frac, centroid)) continue;
        out[n++] = {cell_weights(centroid, cell_layout_), frac / (kSub * kSub * kSub)};
      }
  return n;
}

// Adds the capacity deposits of `cells` (in the order given) to raw. The sub-cubes of the
// cells near walls are evaluated in parallel (the costly part: phi and its gradient), a
// chunk of cells at a time, and added one cell after the other in the given order: the
// same additions in the same order as a serial loop, so raw is bitwise the same for any
// thread count.
void Exchange::add_cell_capacities(const std::vector<std::array<int, 3>>& cells, double r,
                                   const std::vector<unsigned char>& near, fluid::Field& raw) const {
  constexpr size_t kChunk = 1024, kItems = kSub * kSub * kSub;
  std::vector<CapacityItem>& items = scratch_.items;  // grown once, never cleared
  std::vector<int>& count = scratch_.count;           // -1: a plain cell
  const size_t chunk = std::min(cells.size(), kChunk);
  if (items.size() < chunk * kItems) items.resize(chunk * kItems);
  if (count.size() < chunk) count.resize(chunk);
  for (size_t c0 = 0; c0 < cells.size(); c0 += kChunk) {
    const long m = static_cast<long>(std::min(kChunk, cells.size() - c0));
#pragma omp parallel for schedule(dynamic, 16)
    for (long q = 0; q < m; ++q) {
      const auto [i, j, k] = cells[c0 + q];
      count[q] = plain_cell(i, j, k, near) ? -1 : cell_capacity_items(i, j, k, r, &items[q * kItems]);
    }
    for (long q = 0; q < m; ++q) {
      const auto [i, j, k] = cells[c0 + q];
      if (count[q] < 0) deposit_plain_capacity(i, j, k, raw);
      for (int e = 0; e < count[q]; ++e) deposit(items[q * kItems + e].w, items[q * kItems + e].v, raw);
    }
  }
}

Exchange::CapacityCache* Exchange::capacity_cache(double r) const {
  if (sync_ || !(frame_ && frame_->scene && !frame_->scene->empty())) return nullptr;
  const auto it = std::find(radii_.begin(), radii_.end(), r);
  if (it == radii_.end()) return nullptr;
  capacity_cache_.resize(radii_.size());
  CapacityCache& c = capacity_cache_[it - radii_.begin()];
  const geometry::Scene& scene = *frame_->scene;
  if (!(c.scene == &scene && c.walls == walls_ && scene.same_static_placement(c.offsets, frame_->offset))) {
    c.scene = &scene, c.walls = walls_, c.offsets = frame_->offset;
    c.value = fluid::make_cell_field(g_);
    c.known.assign(static_cast<size_t>(g_.nx) * g_.ny * g_.nz, 0);
    c.recent.assign(c.known.size(), 0);
  }
  if (!(c.recent_offsets == frame_->offset)) {  // something moved: the recent values are stale
    c.recent_offsets = frame_->offset;
    std::fill(c.recent.begin(), c.recent.end(), 0);
  }
  return &c;
}

std::array<long, 2> Exchange::capacity(double r, const fluid::Field& solid, fluid::Field& cap) const {
  const std::array<int, 3> n = g_.n();
  // Nodes that need it: holding solid, with a non-plain cell within the kernel's reach.
  // A cell is plain when no wall lies within the kernel's reach of any point of it nor
  // within r + (its half-diagonal) of its centre: no cell within `reach` of it holds wall
  // (one cell more than that distance needs, for walls thinner than the wall fractions'
  // sampling resolves), and it is not at a domain end.
  const int reach = 1 + static_cast<int>(std::floor(r / g_.dx + 0.5 * std::sqrt(3.0) + 0.5));
  const std::vector<unsigned char> near = near_walls(reach);
  auto is_plain = [&](int i, int j, int k) { return plain_cell(i, j, k, near); };
  auto wrap = [&](int e, int m) { return periodic_[e] ? (m % n[e] + n[e]) % n[e] : m; };
  auto inside = [&](int e, int m) {
    const int lo = cells_.ghost_side[2 * e] ? -1 : 0, hi = cells_.ghost_side[2 * e + 1] ? n[e] : n[e] - 1;
    return periodic_[e] || (m >= lo && m <= hi);
  };
  // need, per padded cell index (cell_layout_): 1 where the node's capacity is evaluated
  const auto at = [&](int i, int j, int k) { return static_cast<size_t>(cell_layout_.index(i, j, k)); };
  std::vector<unsigned char>& need = scratch_.need;
  need.assign(cell_layout_.size(), 0);
  // Over the block's own nodes and, on cut sides, its ghost layer: the neighbour's cells
  // that reach a node near the cut deposit there from the neighbour (sum_deposits).
  std::array<int, 3> lo{}, hi{};
  for (int e = 0; e < 3; ++e) lo[e] = cells_.ghost_side[2 * e] ? -1 : 0, hi[e] = cells_.ghost_side[2 * e + 1] ? n[e] : n[e] - 1;
  bool any = false;
#pragma omp parallel for schedule(static) if (g_.cells() > fluid::kOmpMinWork) reduction(|| : any)
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        if (!(solid(i, j, k) > 0)) continue;
        bool all_plain = true;
        for (int c = -1; c <= 1 && all_plain; ++c)
          for (int b = -1; b <= 1 && all_plain; ++b)
            for (int a = -1; a <= 1 && all_plain; ++a) {
              if (!inside(0, i + a) || !inside(1, j + b) || !inside(2, k + c)) continue;
              all_plain = is_plain(wrap(0, i + a), wrap(1, j + b), wrap(2, k + c));
            }
        if (all_plain) continue;
        need[at(i, j, k)] = 1;
        any = true;
      }
  cap.fill(1.0);
  std::array<long, 2> nodes{};  // from the cache, evaluated
  if (!(sync_ ? sync_->any(any) : any)) return nodes;
  // A node's capacity is the sum of what the cells around it deposit there, in the same
  // order whichever other nodes are evaluated, and it depends on the walls within
  // reach + 1 cells of it (the plain test of its cells), 2 cells (the masked weights of its
  // cells' sub-cubes) and a half-diagonal more (the sampled wall fractions of those cells).
  // Where no moving part's bounds come that near, it is the static walls' value: taken
  // from the cache when known (bit for bit what evaluating it gives), else evaluated and
  // kept. Where one does, the value is taken from the cache if the last call evaluated it
  // with every body where it is now (nothing moved since), else evaluated and kept for the
  // next call. need = 2 marks a node whose capacity came from the cache.
  CapacityCache* cache = capacity_cache(r);
  std::vector<unsigned char>& keep = scratch_.keep;  // per own cell: an evaluated capacity to be kept
  if (cache) {
    const geometry::Scene& scene = *frame_->scene;
    // The moving parts' bounds widened by the margin, with their images across the ends of
    // periodic axes (the kernel reaches across them).
    std::vector<geometry::Aabb> moving;
    const double m = (reach + 2) * g_.dx;
    for (int p = 0; p < static_cast<int>(scene.parts().size()); ++p) {
      if (scene.part_is_static(p)) continue;
      const geometry::Aabb b = frame_->part_bounds(p);
      for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy)
          for (int sz = -1; sz <= 1; ++sz) {
            if ((sx && !periodic_[0]) || (sy && !periodic_[1]) || (sz && !periodic_[2])) continue;
            const Vec3 s{sx * n[0] * g_.dx, sy * n[1] * g_.dx, sz * n[2] * g_.dx};
            moving.push_back({b.lo - Vec3{m, m, m} + s, b.hi + Vec3{m, m, m} + s});
          }
    }
    keep.assign(static_cast<size_t>(n[0]) * n[1] * n[2], 0);
    any = false;
    long from_cache = 0;
#pragma omp parallel for schedule(static) if (g_.cells() > fluid::kOmpMinWork) reduction(|| : any) reduction(+ : from_cache)
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          if (need[at(i, j, k)] != 1) continue;
          const Vec3 x = g_.cell_centre(i, j, k);
          bool reached = false;
          for (const auto& b : moving) reached = reached || b.contains(x);
          const size_t q = i + static_cast<size_t>(n[0]) * (j + static_cast<size_t>(n[1]) * k);
          if ((!reached && cache->known[q]) || cache->recent[q]) {
            cap(i, j, k) = cache->value(i, j, k);
            need[at(i, j, k)] = 2;
            ++from_cache;
            continue;
          }
          keep[q] = !reached;
          any = true;
        }
    nodes[0] = from_cache;
    if (!any) return nodes;
  }
  // Every cell within the reach of an evaluated node deposits (in index order: serial,
  // deterministic); the nodes' capacities are then complete.
  fluid::Field& raw = scratch_.raw;
  raw.resize(n[0], n[1], n[2]);  // zeroed, in the storage of the last call
  std::vector<unsigned char>& dep = scratch_.dep;  // per padded cell index: 1 where a cell deposits
  dep.assign(cell_layout_.size(), 0);
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        if (need[at(i, j, k)] != 1) continue;
        for (int c = -1; c <= 1; ++c)
          for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a) {
              const int x = wrap(0, i + a), y = wrap(1, j + b), z = wrap(2, k + c);
              if (x < 0 || x >= n[0] || y < 0 || y >= n[1] || z < 0 || z >= n[2]) continue;  // own cells only
              dep[at(x, y, z)] = 1;
            }
      }
  std::vector<std::array<int, 3>>& cells = scratch_.cells;
  cells.clear();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (dep[at(i, j, k)] == 1) cells.push_back({i, j, k});
  add_cell_capacities(cells, r, near, raw);
  if (sync_) sync_->sum_deposits(raw, fluid::kCells);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (need[at(i, j, k)] != 1) continue;
        cap(i, j, k) = raw(i, j, k);
        ++nodes[1];
        const size_t q = i + static_cast<size_t>(n[0]) * (j + static_cast<size_t>(n[1]) * k);
        if (cache) cache->value(i, j, k) = raw(i, j, k), cache->known[q] = keep[q], cache->recent[q] = 1;
      }
  return nodes;
}

}  // namespace cgdem::coupling
