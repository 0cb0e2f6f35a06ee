#include "fluid/ibm.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace cgdem::fluid {

namespace {

using geometry::Aabb;
using geometry::Scene;

struct Parts {
  std::vector<int> fixed, moving;  // part indices of static / moving bodies, in scene order
};

Parts split_parts(const Scene& scene) {
  Parts p;
  for (size_t i = 0; i < scene.parts().size(); ++i)
    (scene.part_is_static(static_cast<int>(i)) ? p.fixed : p.moving).push_back(static_cast<int>(i));
  return p;
}

// Centre of box q of array a (0: cells, 1 + d: d-faces).
Vec3 box_centre(const MacGrid& g, int a, int i, int j, int k) {
  return a == 0 ? g.cell_centre(i, j, k) : g.face_centre(a - 1, i, j, k);
}

std::array<int, 3> box_extent(const MacGrid& g, int a) { return a == 0 ? g.n() : g.face_extent(a - 1); }

// min over `parts` of the signed distance at x, and the first part reaching it (-1 if none).
double nearest_of(const Scene::Frame& f, const std::vector<int>& parts, const Vec3& x, int& which) {
  double m = INFINITY;
  which = -1;
  for (int p : parts) {
    const double d = f.part_distance(p, x);
    if (d < m) m = d, which = p;
  }
  return m;
}

// Fraction of the cube [x - h, x + h] inside the walls when the union of `parts` is all that
// can cover it: the box and sample positions of Scene::Frame::solid_fraction (n^3 midpoints),
// each sample tested only against the parts whose bounds contain it. A box-shaped part
// (Shape::axis_separable) is tested axis by axis: the samples lie on a lattice, so its n
// coordinates per axis are tested once each (bounds and interior, the same comparisons as
// the per-sample test) and a sample is inside when its three are. Same count, bit for bit.
double sampled_fraction(const Scene::Frame& f, const std::vector<int>& parts, const std::vector<Aabb>& bounds,
                        const Vec3& x, double h, int n) {
  const Vec3 lo = x - Vec3{h, h, h}, hi = x + Vec3{h, h, h};
  constexpr int kMaxN = 16, kMaxSep = 32;  // n <= 16 (update_ibm); parts beyond 32: per sample
  std::array<std::array<double, kMaxN>, 3> coord;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < n; ++i) coord[a][i] = lo[a] + (i + 0.5) * (hi[a] - lo[a]) / n;
  // per box-shaped candidate: bit i of mask[a] set when coordinate i of axis a is in it
  std::array<std::array<unsigned, 3>, kMaxSep> mask;
  std::array<bool, kMaxSep> any_in{}, separable{};
  int boxes = 0;
  bool others = false;
  for (size_t q = 0; q < parts.size(); ++q) {
    if (q < kMaxSep) separable[q] = f.part_separable(parts[q]);
    if (!(q < kMaxSep && separable[q])) {
      others = true;
      continue;
    }
    auto& m = mask[boxes];
    for (int a = 0; a < 3; ++a) {
      m[a] = 0;
      for (int i = 0; i < n; ++i) {
        const double c = coord[a][i];
        if (c >= bounds[q].lo[a] && c <= bounds[q].hi[a] && f.part_inside_along(parts[q], a, c)) m[a] |= 1u << i;
      }
    }
    any_in[boxes] = m[0] && m[1] && m[2];
    ++boxes;
  }
  // Row (j, k) of samples: bit i of `row` set when sample (i, j, k) is in a box-shaped part,
  // the union of those parts' x masks whose y and z masks hold j and k. Counted whole; the
  // other samples of the row are tested against the other parts one by one.
  int inside = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      unsigned row = 0;
      for (int b = 0; b < boxes; ++b)
        if (any_in[b] && ((mask[b][1] >> j) & (mask[b][2] >> k) & 1u)) row |= mask[b][0];
      inside += std::popcount(row);
      if (!others) continue;
      for (int i = 0; i < n; ++i) {
        if ((row >> i) & 1u) continue;
        const Vec3 s{coord[0][i], coord[1][j], coord[2][k]};
        for (size_t q = 0; q < parts.size(); ++q)
          if (!(q < kMaxSep && separable[q]) && bounds[q].contains(s) && f.part_distance(parts[q], s) < 0) {
            ++inside;
            break;
          }
      }
    }
  return static_cast<double>(inside) / (n * n * n);
}

// The fraction of a box of half-width h whose centre lies at signed distance pc from the
// walls, when no sample is needed (the exact 0 / 1 shortcuts of solid_fraction: the box lies
// wholly outside or inside); -1 when it must be sampled.
double sure_fraction(double pc, double h) {
  const double half_diag = 0.5 * norm(Vec3{2 * h, 2 * h, 2 * h});
  if (pc >= half_diag) return 0.0;
  if (pc <= -half_diag) return 1.0;
  return -1.0;
}

// Box fraction with phi at the centre given (phi over `parts`): sure_fraction, else the samples.
double box_fraction(const Scene::Frame& f, const std::vector<int>& parts, const std::vector<Aabb>& bounds,
                    const Vec3& x, double pc, double h, int n, long& sampled) {
  if (const double sure = sure_fraction(pc, h); sure >= 0) return sure;
  ++sampled;
  return sampled_fraction(f, parts, bounds, x, h, n);
}

// The parts of `all` whose bounds come within r of x. Returns the least distance from x to
// the bounds of the others (+inf if none).
double candidates(const std::vector<int>& all, const std::vector<Aabb>& bounds, const Vec3& x, double r,
                  std::vector<int>& out, std::vector<Aabb>& out_b) {
  out.clear(), out_b.clear();
  double far = INFINITY;
  for (size_t q = 0; q < all.size(); ++q) {
    const double bd = bounds[q].distance(x);
    if (bd <= r)
      out.push_back(all[q]), out_b.push_back(bounds[q]);
    else
      far = std::min(far, bd);
  }
  return far;
}

// Fills the static cache: every box of every array against the static parts only.
void build_static(const MacGrid& g, const Scene::Frame& frame, const Parts& parts, int samples,
                  IbmFractions::StaticCache& c, long& sampled) {
  std::vector<Aabb> fb;
  for (int p : parts.fixed) fb.push_back(frame.part_bounds(p));
  const double h = 0.5 * g.dx, r = 0.5 * norm(Vec3{g.dx, g.dx, g.dx});
  bool any = false;
  for (int a = 0; a < 4; ++a) {
    const std::array<int, 3> e = box_extent(g, a);
    c.alpha[a] = Field(e);
    c.phi[a] = Field(e, INFINITY);
    c.nearest[a].assign(static_cast<size_t>(e[0]) * e[1] * e[2], -1);
    if (a > 0) c.ub[a - 1] = Field(e);
#pragma omp parallel for schedule(dynamic) if (g.cells() > kOmpMinWork) reduction(+ : sampled) reduction(|| : any)
    for (int k = 0; k < e[2]; ++k) {
      std::vector<int> cand;
      std::vector<Aabb> cand_b;
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          const Vec3 x = box_centre(g, a, i, j, k);
          int which;
          const double ps = nearest_of(frame, parts.fixed, x, which);
          c.phi[a](i, j, k) = ps;
          c.nearest[a][i + static_cast<size_t>(e[0]) * (j + static_cast<size_t>(e[1]) * k)] = which;
          candidates(parts.fixed, fb, x, r, cand, cand_b);
          const double al = box_fraction(frame, cand, cand_b, x, ps, h, samples, sampled);
          c.alpha[a](i, j, k) = al;
          if (al > 0) {
            any = true;
            if (a > 0) c.ub[a - 1](i, j, k) = frame.part_velocity(which)[a - 1];
          }
        }
    }
  }
  c.any = any;
}

// Index range [lo, hi) along axis d of the boxes of array a whose centres lie in [x0, x1].
std::array<int, 2> index_range(const MacGrid& g, int a, int d, double x0, double x1, int n) {
  const double off = (a == d + 1) ? 0.0 : 0.5;  // face arrays sit on the lines along their axis
  const double o = g.origin[d];
  const double lo = std::clamp(std::floor((x0 - o) / g.dx - off), -1.0, double(n)),
               hi = std::clamp(std::ceil((x1 - o) / g.dx - off) + 1, 0.0, double(n));
  return {static_cast<int>(lo), static_cast<int>(hi) < 0 ? 0 : static_cast<int>(hi)};
}

}  // namespace

bool update_ibm(const MacGrid& g, const geometry::Scene::Frame& frame, int samples, IbmFractions& ibm) {
  if (samples < 1 || samples > 16) throw Error("IBM: the number of sub-samples per axis must be 1..16");
  if (ibm.valid && ibm.offsets == frame.offset) return false;
  ibm.offsets = frame.offset;
  ibm.valid = true;
  ibm.sampled_faces = 0;
  if (frame.scene == nullptr || frame.scene->empty()) {
    for (int d = 0; d < 3; ++d) {
      ibm.alpha_face[d] = make_face_field(g, d);
      ibm.ub_face[d] = make_face_field(g, d);
    }
    ibm.alpha_cell = make_cell_field(g);
    ibm.any_solid = false;
    ibm.cache = {};
    return true;
  }
  const Scene& scene = *frame.scene;
  const Parts parts = split_parts(scene);
  auto& c = ibm.cache;
  const bool same_static = c.valid && c.scene == &scene && c.samples == samples && c.n == g.n() &&
                           scene.same_static_placement(c.offsets, frame.offset);
  long sampled = 0;
  if (!same_static) {
    build_static(g, frame, parts, samples, c, sampled);
    c.scene = &scene, c.offsets = frame.offset, c.samples = samples, c.n = g.n(), c.valid = true;
    c.have_region = false;
    ibm.alpha_cell = c.alpha[0];
    for (int d = 0; d < 3; ++d) ibm.alpha_face[d] = c.alpha[d + 1], ibm.ub_face[d] = c.ub[d];
  }
  // Region to re-evaluate: the moving parts' bounds now and at the last call.
  std::vector<Aabb> mb, fb;
  for (int p : parts.moving) mb.push_back(frame.part_bounds(p));
  for (int p : parts.fixed) fb.push_back(frame.part_bounds(p));
  const double h = 0.5 * g.dx, r = 0.5 * norm(Vec3{g.dx, g.dx, g.dx});
  bool any = c.any;
  // The kept boxes (header): reset with the static cache, else the travel since the last call
  // is added to the path. The round-off of phi and of the sums is far below eps.
  int moving_body = -1;  // the one body the moving parts belong to (-1: several)
  for (size_t q = 0; q < parts.moving.size(); ++q) {
    const int b = scene.parts()[parts.moving[q]].body;
    moving_body = q == 0 ? b : (b == moving_body ? b : -1);
    if (moving_body < 0) break;
  }
  const bool keep = ibm.keep_far && !mb.empty();
  const std::array<int, 3> ec = box_extent(g, 0);
  const bool sized = c.kept_kind[0].size() == static_cast<size_t>(ec[0]) * ec[1] * ec[2];
  if (!same_static || c.path_offsets.size() != frame.offset.size() || !keep || !sized) {
    for (int a = 0; a < 4; ++a) {
      const std::array<int, 3> e = box_extent(g, a);
      c.kept_kind[a].assign(keep ? static_cast<size_t>(e[0]) * e[1] * e[2] : 0, 0);
      c.kept_until[a].assign(c.kept_kind[a].size(), -INFINITY);
    }
    c.path = 0;
  } else {
    double step = 0;
    for (size_t b = 0; b < frame.offset.size(); ++b)
      if (!scene.bodies()[b].motion.is_static()) step = std::max(step, norm(frame.offset[b] - c.path_offsets[b]));
    c.path += step;
  }
  c.path_offsets = frame.offset;
  const double eps = 1e-9 * g.dx, h_d = 0.5 * norm(Vec3{2 * h, 2 * h, 2 * h});  // sure_fraction's half-diagonal
  long kept = 0;
  if (!mb.empty()) {
    Aabb reg{mb[0].lo, mb[0].hi};
    for (const Aabb& b : mb) reg.lo = cmin(reg.lo, b.lo), reg.hi = cmax(reg.hi, b.hi);
    Aabb now = reg;
    if (c.have_region) reg.lo = cmin(reg.lo, c.region.lo), reg.hi = cmax(reg.hi, c.region.hi);
    c.region = now, c.have_region = true;
    const double m = r + g.dx;
    for (int a = 0; a < 4; ++a) {
      const std::array<int, 3> e = box_extent(g, a);
      std::array<std::array<int, 2>, 3> ir;
      for (int d = 0; d < 3; ++d) ir[d] = index_range(g, a, d, reg.lo[d] - m, reg.hi[d] + m, e[d]);
      ir[0][0] = std::max(ir[0][0], 0), ir[1][0] = std::max(ir[1][0], 0), ir[2][0] = std::max(ir[2][0], 0);
      Field& al_out = a == 0 ? ibm.alpha_cell : ibm.alpha_face[a - 1];
      const long work = long(ir[0][1] - ir[0][0]) * (ir[1][1] - ir[1][0]) * (ir[2][1] - ir[2][0]);
      unsigned char* kind = keep ? c.kept_kind[a].data() : nullptr;
      double* until = keep ? c.kept_until[a].data() : nullptr;
#pragma omp parallel for schedule(dynamic) if (work > kOmpMinWork / 4) reduction(+ : sampled, kept) reduction(|| : any)
      for (int k = ir[2][0]; k < ir[2][1]; ++k) {
        std::vector<int> cm, cs, call;
        std::vector<Aabb> cmb, csb, callb;
        for (int j = ir[1][0]; j < ir[1][1]; ++j)
          for (int i = ir[0][0]; i < ir[0][1]; ++i) {
            const size_t q = i + static_cast<size_t>(e[0]) * (j + static_cast<size_t>(e[1]) * k);
            if (kind && kind[q] != 0 && c.path <= until[q]) {  // the value stands (header)
              ++kept;
              if (kind[q] == 2) {
                any = true;
                if (a > 0) ibm.ub_face[a - 1](i, j, k) = frame.velocity[moving_body][a - 1];
              }
              continue;
            }
            const Vec3 x = box_centre(g, a, i, j, k);
            const double far = candidates(parts.moving, mb, x, r, cm, cmb);
            double al;
            int which = c.nearest[a][q];
            double dist = c.phi[a](i, j, k);
            double pm = INFINITY;  // phi of the moving parts within reach (+inf: none)
            if (cm.empty()) {
              al = c.alpha[a](i, j, k);  // no moving part within reach: the static value
            } else {
              int wm;
              pm = nearest_of(frame, cm, x, wm);
              const double pc = std::min(dist, pm);
              if (pm < dist || (pm == dist && wm < which)) which = wm, dist = pm;
              if (const double sure = sure_fraction(pc, h); sure >= 0) {
                al = sure;  // the static parts near it are gathered only to sample
              } else {
                candidates(parts.fixed, fb, x, r, cs, csb);
                call = cs, callb = csb;
                call.insert(call.end(), cm.begin(), cm.end());
                callb.insert(callb.end(), cmb.begin(), cmb.end());
                al = box_fraction(frame, call, callb, x, pc, h, samples, sampled);
              }
            }
            al_out(i, j, k) = al;
            if (al > 0) any = true;
            if (a > 0) ibm.ub_face[a - 1](i, j, k) = al > 0 ? frame.part_velocity(which)[a - 1] : 0.0;
            if (!kind) continue;
            // Its clearance outside every moving part: the parts within reach stay h_d away
            // (phi moves by at most the travel), the others out of reach (their bounds move by
            // the travel; a CSG phi may be below the distance to the bounds, so the bounds'
            // distance is not used as a phi). Or its clearance inside the one moving body.
            const double static_phi = c.phi[a](i, j, k), clear = std::min(pm - h_d, far - r) - eps;
            kind[q] = 0;
            if (clear >= 0) {
              kind[q] = 1, until[q] = c.path + clear;
            } else if (moving_body >= 0 && pm <= -h_d - eps && pm < static_phi - eps) {
              kind[q] = 2, until[q] = c.path + std::min(-pm - h_d - eps, static_phi - pm - eps);
            }
          }
      }
    }
  }
  ibm.any_solid = any;
  ibm.sampled_faces = sampled;
  ibm.kept_boxes = kept;
  return true;
}

}  // namespace cgdem::fluid
