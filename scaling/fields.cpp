#include "scaling/fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "io/h5_util.hpp"
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
    io::h5::Id file = io::h5::open_file(f);
    out.push_back({io::h5::read_double_attribute(file, "time", f), f});
  }
  std::stable_sort(out.begin(), out.end(), [](const Frame& a, const Frame& b) { return a.t < b.t; });
  return out;
}

std::vector<double> read_cell_field(const std::string& f, const std::string& name, Grid* g) {
  io::h5::Id file = io::h5::open_file(f);
  std::vector<hsize_t> dims;
  if (g) {
    auto n = io::h5::read_int64(file, "grid/n", dims, f);
    auto o = io::h5::read_double(file, "grid/origin", dims, f);
    auto h = io::h5::read_double(file, "grid/spacing", dims, f);
    if (n.size() != 3 || o.size() != 3 || h.size() != 3) throw Error(f + ": /grid/n, origin, spacing must have 3 values");
    g->nx = static_cast<int>(n[0]), g->ny = static_cast<int>(n[1]), g->nz = static_cast<int>(n[2]);
    g->origin = {o[0], o[1], o[2]};
    g->dx = h[0];
  }
  if (!io::h5::exists(file, "cells/" + name)) throw Error(fmt::format("{}: no cell field '{}'", f, name));
  return io::h5::read_double(file, "cells/" + name, dims, f);
}

}  // namespace cgdem::scaling
