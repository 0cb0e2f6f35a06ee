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

BubbleCensus find_bubbles(const MacGrid& g, const Field& eps, const Field& alpha_cell, const FluidBoundary& bc,
                          double eps_air, long min_cells, double z_split) {
  if (eps.extent() != g.n() || alpha_cell.extent() != g.n())
    throw Error("find_bubbles: eps and alpha_cell must be cell fields of the grid");
  enum : uint8_t { kWall = 0, kPowder = 1, kAir = 2 };
  const long n = g.cells();
  auto flat = [&](int i, int j, int k) { return i + static_cast<long>(g.nx) * (j + static_cast<long>(g.ny) * k); };
  std::vector<uint8_t> kind(n);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const long c = flat(i, j, k);
        if (alpha_cell(i, j, k) >= 0.5) kind[c] = kWall;
        else kind[c] = eps(i, j, k) >= eps_air ? kAir : kPowder;
      }

  const std::array<int, 3> nn = g.n();
  std::vector<uint8_t> seen(n, 0);
  std::vector<std::array<int, 3>> stack;
  BubbleCensus out;
  const double cell_volume = g.dx * g.dx * g.dx;
  for (int k0 = 0; k0 < g.nz; ++k0)
    for (int j0 = 0; j0 < g.ny; ++j0)
      for (int i0 = 0; i0 < g.nx; ++i0) {
        const long c0 = flat(i0, j0, k0);
        if (kind[c0] != kAir || seen[c0]) continue;
        // Flood one region through face neighbours (periodic axes wrap).
        bool open = false, touches_powder = false;
        Bubble b;
        Vec3 moment{};
        seen[c0] = 1;
        stack.assign(1, {i0, j0, k0});
        while (!stack.empty()) {
          const std::array<int, 3> q = stack.back();
          stack.pop_back();
          const double v = (1.0 - alpha_cell(q[0], q[1], q[2])) * eps(q[0], q[1], q[2]) * cell_volume;
          const Vec3 x = g.cell_centre(q[0], q[1], q[2]);
          b.volume += v;
          if (x.z > z_split) b.volume_above += v;
          moment += v * x;
          b.z_top = std::max(b.z_top, x.z + 0.5 * g.dx);
          ++b.cells;
          for (int d = 0; d < 3; ++d)
            for (int h = 0; h < 2; ++h) {
              std::array<int, 3> r = q;
              r[d] += h ? 1 : -1;
              if (r[d] < 0 || r[d] >= nn[d]) {
                const BcType t = bc[2 * d + h].type;
                if (t == BcType::Open) {
                  open = true;
                  continue;
                }
                if (t != BcType::Periodic) continue;
                r[d] = (r[d] + nn[d]) % nn[d];
              }
              const long c = flat(r[0], r[1], r[2]);
              if (kind[c] == kPowder) touches_powder = true;
              if (kind[c] != kAir || seen[c]) continue;
              seen[c] = 1;
              stack.push_back(r);
            }
        }
        if (open || b.cells < min_cells) continue;
        b.centroid = b.volume > 0 ? (1.0 / b.volume) * moment : g.cell_centre(i0, j0, k0);
        if (touches_powder) out.bubbles.push_back(b);
        else out.sealed_volume += b.volume;
      }
  std::stable_sort(out.bubbles.begin(), out.bubbles.end(),
                   [](const Bubble& a, const Bubble& b) { return a.volume > b.volume; });
  return out;
}

}  // namespace cgdem::fluid
