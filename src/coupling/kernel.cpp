#include "coupling/kernel.hpp"

#include <cmath>

namespace cgdem::coupling {

Lattice cell_lattice(const fluid::MacGrid& g, std::array<bool, 3> periodic) {
  return {g.origin + 0.5 * g.dx * Vec3{1, 1, 1}, g.dx, g.n(), periodic};
}

Lattice face_lattice(const fluid::MacGrid& g, int d, std::array<bool, 3> periodic) {
  Lattice L = cell_lattice(g, periodic);
  L.origin[d] = g.origin[d];
  L.n = g.face_extent(d);
  if (periodic[d]) L.n[d] -= 1;  // face n is the image of face 0
  return L;
}

Stencil tsc_stencil(const Lattice& L, const Vec3& x) {
  Stencil s;
  for (int a = 0; a < 3; ++a) {
    const double q = (x[a] - L.origin[a]) / L.h;
    const double i0 = std::nearbyint(q);
    const double t = q - i0;
    s.w[a] = {0.5 * (0.5 - t) * (0.5 - t), 0.75 - t * t, 0.5 * (0.5 + t) * (0.5 + t)};
    const int n = L.n[a];
    for (int m = 0; m < 3; ++m) {
      long i = static_cast<long>(i0) - 1 + m;
      if (L.periodic[a]) {
        i %= n;
        if (i < 0) i += n;
      } else {
        const long lo = L.ghost_side[2 * a] ? -fluid::kGhost : 0;
        const long hi = L.ghost_side[2 * a + 1] ? n - 1 + fluid::kGhost : n - 1;
        i = i < lo ? lo : (i > hi ? hi : i);
      }
      s.idx[a][m] = static_cast<int>(i);
    }
  }
  return s;
}

Weights flatten(const Stencil& s, const fluid::Field& layout) {
  Weights f;
  int n = 0;
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a, ++n) {
        f.idx[n] = layout.index(s.idx[0][a], s.idx[1][b], s.idx[2][c]);
        f.w[n] = s.w[0][a] * s.w[1][b] * s.w[2][c];
      }
  return f;
}

Weights masked(const Stencil& s, const fluid::Field& alpha, const fluid::Field& layout) {
  return masked(s, alpha, fluid::Field{}, layout);
}

Weights masked(const Stencil& s, const fluid::Field& alpha, const fluid::Field& blocked, const fluid::Field& layout) {
  Weights f = flatten(s, layout);
  if (alpha.empty() && blocked.empty()) return f;
  double sum = 0;
  std::array<double, 27> w;
  for (int n = 0; n < 27; ++n) {
    w[n] = f.w[n];
    if (!alpha.empty()) w[n] *= 1 - alpha.data()[f.idx[n]];
    if (!blocked.empty()) w[n] *= 1 - blocked.data()[f.idx[n]];
    sum += w[n];
  }
  if (sum > 1e-12) {
    const double inv = 1 / sum;
    for (int n = 0; n < 27; ++n) f.w[n] = w[n] * inv;
  }
  return f;
}

void deposit(const Weights& s, double value, fluid::Field& f) {
  double* d = f.data();
  for (int n = 0; n < 27; ++n) d[s.idx[n]] += value * s.w[n];
}

double interpolate(const Weights& s, const fluid::Field& f) {
  const double* d = f.data();
  double sum = 0;
  for (int n = 0; n < 27; ++n) sum += s.w[n] * d[s.idx[n]];
  return sum;
}

double interpolate_cell_faces(const Weights& s, const fluid::Field& cell_layout, int d, const fluid::Field& f) {
  // Face i of cell i (its low face) and face i + 1 (its high face): the same (i, j, k) in
  // the face layout, and one step along d.
  const double* v = f.data();
  const long step = f.stride(d);
  double sum = 0;
  for (int n = 0; n < 27; ++n) {
    const long q = s.idx[n];
    // Convert the cell-layout flat index to (i, j, k), then to the face layout.
    const long sy = cell_layout.stride(1), sz = cell_layout.stride(2);
    const long k = q / sz, j = (q - k * sz) / sy, i = q - k * sz - j * sy;
    const long fq = f.index(static_cast<int>(i) - fluid::kGhost, static_cast<int>(j) - fluid::kGhost,
                            static_cast<int>(k) - fluid::kGhost);
    sum += 0.5 * s.w[n] * (v[fq] + v[fq + step]);
  }
  return sum;
}

void sync_periodic_face(int d, std::array<bool, 3> periodic, fluid::Field& f) {
  if (!periodic[d]) return;
  const auto e = f.extent();
  const int n = e[d] - 1;
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i) {
        std::array<int, 3> q{i, j, k};
        if (q[d] != n) continue;
        std::array<int, 3> src = q;
        src[d] = 0;
        f(i, j, k) = f(src[0], src[1], src[2]);
      }
}

}  // namespace cgdem::coupling
