// Manufactured solutions for the variable-coefficient Poisson problem div(a grad phi) = rhs on
// the unit box. phi = X(x) Y(y) Z(z), each factor chosen to satisfy its axis' boundary pair:
//   Wall-Wall  cos(pi t)         Open-Open  sin(pi t)        Periodic  sin(2 pi t + 0.3)
//   Open-Wall  sin(pi t / 2)     Wall-Open  cos(pi t / 2)
// Coefficient a = exp(1.5 cos(2 pi x) cos(2 pi y) cos(2 pi z)): smooth, periodic, contrast
// e^3 ~ 20 (packed bed next to free air). rhs = a lap(phi) + grad(a).grad(phi), exact.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::pressure::test {

// n values in [-1, 1) from a xorshift generator: the same on every machine.
inline std::vector<double> noise(long n, std::uint64_t seed) {
  std::vector<double> v(n);
  for (auto& x : v) {
    seed ^= seed << 13; seed ^= seed >> 7; seed ^= seed << 17;
    x = 2.0 * double(seed >> 11) / double(1ull << 53) - 1.0;
  }
  return v;
}

struct Problem {
  GridSpec g;
  std::vector<double> ax, ay, az, rhs, exact;
};

inline void axis_fn(Boundary lo, Boundary hi, double t, double& f, double& df, double& ddf) {
  const double pi = M_PI;
  double w = pi, ph = 0;
  bool sine = false;
  if (lo == Boundary::Periodic) { w = 2 * pi; ph = 0.3; sine = true; }
  else if (lo == Boundary::Wall && hi == Boundary::Wall) { w = pi; }
  else if (lo == Boundary::Open && hi == Boundary::Open) { w = pi; sine = true; }
  else if (lo == Boundary::Open) { w = pi / 2; sine = true; }
  else { w = pi / 2; }
  const double s = std::sin(w * t + ph), c = std::cos(w * t + ph);
  if (sine) { f = s; df = w * c; ddf = -w * w * s; }
  else { f = c; df = -w * s; ddf = -w * w * c; }
}

inline double coef(double x, double y, double z, double contrast_log = 1.5) {
  const double t = 2 * M_PI;
  return std::exp(contrast_log * std::cos(t * x) * std::cos(t * y) * std::cos(t * z));
}

inline Problem make_problem(int nx, int ny, int nz, std::array<Boundary, 6> bc) {
  Problem p;
  p.g.nx = nx; p.g.ny = ny; p.g.nz = nz;
  p.g.dx = 1.0 / nx; p.g.dy = 1.0 / ny; p.g.dz = 1.0 / nz;
  p.g.bc = bc;
  const double hx = p.g.dx, hy = p.g.dy, hz = p.g.dz;
  p.ax.resize(long(nx + 1) * ny * nz);
  p.ay.resize(long(nx) * (ny + 1) * nz);
  p.az.resize(long(nx) * ny * (nz + 1));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i) p.ax[i + long(nx + 1) * (j + long(ny) * k)] = coef(i * hx, (j + 0.5) * hy, (k + 0.5) * hz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) p.ay[i + long(nx) * (j + long(ny + 1) * k)] = coef((i + 0.5) * hx, j * hy, (k + 0.5) * hz);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p.az[i + long(nx) * (j + long(ny) * k)] = coef((i + 0.5) * hx, (j + 0.5) * hy, k * hz);
  p.rhs.resize(p.g.cells());
  p.exact.resize(p.g.cells());
  const double t = 2 * M_PI;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = (i + 0.5) * hx, y = (j + 0.5) * hy, z = (k + 0.5) * hz;
        double X, dX, ddX, Y, dY, ddY, Z, dZ, ddZ;
        axis_fn(bc[0], bc[1], x, X, dX, ddX);
        axis_fn(bc[2], bc[3], y, Y, dY, ddY);
        axis_fn(bc[4], bc[5], z, Z, dZ, ddZ);
        const double a = coef(x, y, z);
        const double cx = std::cos(t * x), cy = std::cos(t * y), cz = std::cos(t * z);
        const double sx = -t * std::sin(t * x), sy = -t * std::sin(t * y), sz = -t * std::sin(t * z);
        const double gsx = 1.5 * sx * cy * cz, gsy = 1.5 * cx * sy * cz, gsz = 1.5 * cx * cy * sz;
        const double lap = ddX * Y * Z + X * ddY * Z + X * Y * ddZ;
        const double gdot = gsx * dX * Y * Z + gsy * X * dY * Z + gsz * X * Y * dZ;
        const long c = i + long(nx) * (j + long(ny) * k);
        p.rhs[c] = a * (lap + gdot);
        p.exact[c] = X * Y * Z;
      }
  return p;
}

inline double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

// Max-norm error of phi against the exact solution; singular problems compare mean-free parts.
inline double max_error(const std::vector<double>& phi, const std::vector<double>& exact, bool mean_free) {
  const double mp = mean_free ? mean(phi) : 0.0, me = mean_free ? mean(exact) : 0.0;
  double e = 0;
  for (size_t c = 0; c < phi.size(); ++c) e = std::max(e, std::abs((phi[c] - mp) - (exact[c] - me)));
  return e;
}

}  // namespace cgdem::pressure::test
