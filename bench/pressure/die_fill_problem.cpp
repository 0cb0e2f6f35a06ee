// The pressure problem of the die-filling grid shared by the pressure benchmarks; see
// die_fill_problem.hpp.
#include "bench/pressure/die_fill_problem.hpp"

#include <cstdint>

namespace cgdem::bench {

using namespace cgdem::pressure;

namespace {

bool in_box(double x, double y, double z, double x0, double x1, double y0, double y1, double z0, double z1) {
  return x >= x0 && x <= x1 && y >= y0 && y <= y1 && z >= z0 && z <= z1;
}

}  // namespace

DieFillProblem die_fill_problem(int nx, int ny, int nz) {
  DieFillProblem f;
  f.g.nx = nx; f.g.ny = ny; f.g.nz = nz;
  f.g.dx = 84e-3 / nx; f.g.dy = 42e-3 / ny; f.g.dz = 30e-3 / nz;
  f.g.bc = {Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Wall, Boundary::Open};
  const double mu = 1.8e-5, rho = 1.0, dt = 1e-4, d = 125e-6, slip = 0.05, eps_bed = 0.45;
  const double beta_bed = 150 * mu * (1 - eps_bed) * (1 - eps_bed) / (eps_bed * d * d) +
                          1.75 * (1 - eps_bed) * rho * slip / d;
  const double a_bed = eps_bed * eps_bed / (eps_bed * rho / dt + beta_bed), a_air = dt / rho;
  std::vector<double> a(f.g.cells());
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = (i + 0.5) * f.g.dx * 1e3, y = (j + 0.5) * f.g.dy * 1e3, z = (k + 0.5) * f.g.dz * 1e3;
        const bool die = in_box(x, y, z, 37, 47, 6, 36, 2, 14), cavity = in_box(x, y, z, 22, 32, 6, 36, 14, 24);
        const bool table = z < 14 && !die;
        const bool shoe = in_box(x, y, z, 19, 35, 3, 39, 14, 24) && !cavity;
        a[i + long(nx) * (j + long(ny) * k)] = (table || shoe) ? 0.0 : (die || cavity) ? a_bed : a_air;
      }
  auto hm = [](double p, double q) { return (p > 0 && q > 0) ? 2 * p * q / (p + q) : 0.0; };
  auto cell = [&](int i, int j, int k) { return a[i + long(nx) * (j + long(ny) * k)]; };
  f.ax.resize(long(nx + 1) * ny * nz);
  f.ay.resize(long(nx) * (ny + 1) * nz);
  f.az.resize(long(nx) * ny * (nz + 1));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i)
        f.ax[i + long(nx + 1) * (j + long(ny) * k)] =
            hm(cell(i > 0 ? i - 1 : i, j, k), cell(i < nx ? i : nx - 1, j, k));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i)
        f.ay[i + long(nx) * (j + long(ny + 1) * k)] =
            hm(cell(i, j > 0 ? j - 1 : j, k), cell(i, j < ny ? j : ny - 1, k));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        f.az[i + long(nx) * (j + long(ny) * k)] =
            hm(cell(i, j, k > 0 ? k - 1 : k), cell(i, j, k < nz ? k : nz - 1));
  f.rhs.resize(f.g.cells());
  std::uint64_t s = 88172645463325252ull;  // xorshift64: deterministic noise
  for (long c = 0; c < f.g.cells(); ++c) {
    s ^= s << 13; s ^= s >> 7; s ^= s << 17;
    f.rhs[c] = a[c] > 0 ? 2.0 * double(s >> 11) / double(1ull << 53) - 1.0 : 0.0;
  }
  return f;
}

}  // namespace cgdem::bench
