#include "fluid/bubbles.hpp"

#include <algorithm>
#include <cstdint>

#include "core/error.hpp"

namespace cgdem::fluid {

double BubbleCensus::total_volume() const {
  double v = 0;
  for (const auto& b : bubbles) v += b.volume;
  return v;
}

double BubbleCensus::total_volume_above() const {
  double v = 0;
  for (const auto& b : bubbles) v += b.volume_above;
  return v;
}

namespace {

enum : uint8_t { kWall = 0, kPowder = 1, kAir = 2 };

long flat_index(const MacGrid& g, int i, int j, int k) {
  return i + static_cast<long>(g.nx) * (j + static_cast<long>(g.ny) * k);
}

// Each cell's kind: wall (wall fraction >= 0.5), air (eps >= eps_air) or powder.
std::vector<uint8_t> classify_cells(const MacGrid& g, const Field& eps, const Field& alpha_cell, double eps_air) {
  std::vector<uint8_t> kind(g.cells());
#pragma omp parallel for schedule(static) if (g.cells() > kOmpMinWork)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const long c = flat_index(g, i, j, k);
        if (alpha_cell(i, j, k) >= 0.5) kind[c] = kWall;
        else kind[c] = eps(i, j, k) >= eps_air ? kAir : kPowder;
      }
  return kind;
}

// One air region flooded from cell q0 through face neighbours (periodic axes wrap), depth
// first from a stack: its volume, the part above z_split, its top, its cells and its volume
// moment (summed in the order of the flood), whether it reaches an Open side and whether it
// touches powder. Marks its cells in `seen`. Once the region reaches an Open side the sums
// stop (the caller drops open regions; they are most of the air, the room above the shoe).
struct Region {
  Bubble b;
  Vec3 moment{};
  bool open = false, touches_powder = false;
};

Region flood_region(const MacGrid& g, const Field& eps, const Field& alpha_cell, const FluidBoundary& bc,
                    const std::vector<uint8_t>& kind, std::vector<uint8_t>& seen, std::array<int, 3> q0,
                    double z_split, std::vector<std::array<int, 3>>& stack) {
  const std::array<int, 3> nn = g.n();
  const double cell_volume = g.dx * g.dx * g.dx;
  Region reg;
  Bubble& b = reg.b;
  seen[flat_index(g, q0[0], q0[1], q0[2])] = 1;
  stack.assign(1, q0);
  while (!stack.empty()) {
    const std::array<int, 3> q = stack.back();
    stack.pop_back();
    ++b.cells;
    if (!reg.open) {  // a region open to the air outside is no bubble: its sums are not needed
      const double v = (1.0 - alpha_cell(q[0], q[1], q[2])) * eps(q[0], q[1], q[2]) * cell_volume;
      const Vec3 x = g.cell_centre(q[0], q[1], q[2]);
      b.volume += v;
      if (x.z > z_split) b.volume_above += v;
      reg.moment += v * x;
      b.z_top = std::max(b.z_top, x.z + 0.5 * g.dx);
    }
    for (int d = 0; d < 3; ++d)
      for (int h = 0; h < 2; ++h) {
        std::array<int, 3> r = q;
        r[d] += h ? 1 : -1;
        if (r[d] < 0 || r[d] >= nn[d]) {
          const BcType t = bc[2 * d + h].type;
          if (t == BcType::Open) {
            reg.open = true;
            continue;
          }
          if (t != BcType::Periodic) continue;
          r[d] = (r[d] + nn[d]) % nn[d];
        }
        const long c = flat_index(g, r[0], r[1], r[2]);
        if (kind[c] == kPowder) reg.touches_powder = true;
        if (kind[c] != kAir || seen[c]) continue;
        seen[c] = 1;
        stack.push_back(r);
      }
  }
  return reg;
}

}  // namespace

// The regions in the order of their first cell (x fastest); a region that reaches an Open
// side or has fewer than min_cells cells is no bubble; one that touches powder is, the others
// are air sealed by walls alone. Bubbles by volume, largest first (stable).
BubbleCensus find_bubbles(const MacGrid& g, const Field& eps, const Field& alpha_cell, const FluidBoundary& bc,
                          double eps_air, long min_cells, double z_split) {
  if (eps.extent() != g.n() || alpha_cell.extent() != g.n())
    throw Error("find_bubbles: eps and alpha_cell must be cell fields of the grid");
  const std::vector<uint8_t> kind = classify_cells(g, eps, alpha_cell, eps_air);
  std::vector<uint8_t> seen(g.cells(), 0);
  std::vector<std::array<int, 3>> stack;
  BubbleCensus out;
  for (int k0 = 0; k0 < g.nz; ++k0)
    for (int j0 = 0; j0 < g.ny; ++j0)
      for (int i0 = 0; i0 < g.nx; ++i0) {
        const long c0 = flat_index(g, i0, j0, k0);
        if (kind[c0] != kAir || seen[c0]) continue;
        Region reg = flood_region(g, eps, alpha_cell, bc, kind, seen, {i0, j0, k0}, z_split, stack);
        Bubble& b = reg.b;
        if (reg.open || b.cells < min_cells) continue;
        b.centroid = b.volume > 0 ? (1.0 / b.volume) * reg.moment : g.cell_centre(i0, j0, k0);
        if (reg.touches_powder) out.bubbles.push_back(b);
        else out.sealed_volume += b.volume;
      }
  std::stable_sort(out.bubbles.begin(), out.bubbles.end(),
                   [](const Bubble& a, const Bubble& b) { return a.volume > b.volume; });
  return out;
}

}  // namespace cgdem::fluid
