#include "scaling/fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "io/air_snapshot_reader.hpp"
#include "io/xdmf_series.hpp"

namespace cgdem::scaling {

Grid grid_over(Vec3 lo, Vec3 hi, double dx, std::array<bool, 3> periodic) {
  if (!(dx > 0)) throw Error(fmt::format("grid: cell size {:g} m must be positive", dx));
  Grid g;
  g.origin = lo;
  g.dx = dx;
  g.nx = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / dx - 1e-9)));
  g.ny = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / dx - 1e-9)));
  g.nz = std::max(1, static_cast<int>(std::ceil((hi.z - lo.z) / dx - 1e-9)));
  g.periodic = periodic;
  return g;
}

std::vector<double> solid_fraction(const io::ParticleTable& t, const Grid& g) {
  std::vector<double> phi(static_cast<size_t>(g.cells()), 0.0);
  const int n[3] = {g.nx, g.ny, g.nz};
  const double cell_volume = g.dx * g.dx * g.dx;
  for (size_t p = 0; p < t.size(); ++p) {
    const double V = std::numbers::pi * t.d[p] * t.d[p] * t.d[p] / 6;
    const double x[3] = {t.x[p].x - g.origin.x, t.x[p].y - g.origin.y, t.x[p].z - g.origin.z};
    int i0[3];
    double w1[3];
    for (int a = 0; a < 3; ++a) {
      const double s = x[a] / g.dx - 0.5;  // in cell-centre units
      const double f = std::floor(s);
      i0[a] = static_cast<int>(f);
      w1[a] = s - f;  // weight of the upper neighbour
    }
    for (int c = 0; c < 8; ++c) {
      double w = 1;
      int idx[3];
      for (int a = 0; a < 3; ++a) {
        const int up = (c >> a) & 1;
        w *= up ? w1[a] : 1 - w1[a];
        int i = i0[a] + up;
        if (g.periodic[a]) i = ((i % n[a]) + n[a]) % n[a];
        else i = std::clamp(i, 0, n[a] - 1);
        idx[a] = i;
      }
      phi[static_cast<size_t>(idx[0] + g.nx * (idx[1] + static_cast<long>(g.ny) * idx[2]))] += w * V / cell_volume;
    }
  }
  return phi;
}

std::vector<Frame> list_frames(const std::string& dir, const std::string& prefix) {
  std::vector<Frame> out;
  for (int64_t s : io::find_snapshot_steps(dir, prefix)) {
    const std::string f = dir + "/" + io::snapshot_file_name(prefix, s);
    out.push_back({io::read_snapshot_time(f), f});
  }
  std::stable_sort(out.begin(), out.end(), [](const Frame& a, const Frame& b) { return a.t < b.t; });
  return out;
}

std::vector<double> read_cell_field(const std::string& f, const std::string& name, Grid* g) {
  io::AirSnapshot s = io::read_air_snapshot(f, {name});
  if (!s.scalars.count(name)) throw Error(fmt::format("{}: cell field '{}' is a vector, a scalar is needed", f, name));
  if (g) {
    g->nx = static_cast<int>(s.grid.n[0]), g->ny = static_cast<int>(s.grid.n[1]), g->nz = static_cast<int>(s.grid.n[2]);
    g->origin = s.grid.origin;
    g->dx = s.grid.spacing.x;
  }
  return std::move(s.scalars.at(name));
}

}  // namespace cgdem::scaling
