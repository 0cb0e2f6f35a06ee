#include "fluid/boundary.hpp"

#include <fmt/format.h>

namespace cgdem::fluid {

namespace {

// Lines below this stay on one thread (a parallel region costs a few microseconds; the 140 x
// 70 x 50 air grid has 4,000-10,700 lines per axis).
constexpr long kMinParallelLines = 2048;

const char* side_name(int s) {
  static const char* names[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
  return names[s];
}

// Calls fn(line_base_index) for every line along axis a over the padded extent of the other
// two axes of f. A line's ghosts are written from that line alone, so the lines are shared
// between the threads (planes of lines) without changing a bit; the fill of each line is a
// few scattered stores, latency-bound, which is why even a few thousand lines are worth a
// second thread.
template <class Fn>
void for_each_line(const Field& f, int a, Fn fn) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  std::array<int, 3> e = f.extent();
  const long lines = static_cast<long>(e[b] + 2 * kGhost) * (e[c] + 2 * kGhost);
#pragma omp parallel for schedule(static) if (lines >= kMinParallelLines)
  for (int q = -kGhost; q < e[c] + kGhost; ++q)
    for (int p = -kGhost; p < e[b] + kGhost; ++p) {
      std::array<int, 3> idx{};
      idx[a] = 0, idx[b] = p, idx[c] = q;
      fn(f.index(idx[0], idx[1], idx[2]));
    }
}

// Ghosts along axis a of a face field whose faces are normal to a (component a); n cells.
void fill_normal(Field& f, int a, int n, const SideBc& lo, const SideBc& hi) {
  const long st = f.stride(a);
  double* d = f.data();
  for_each_line(f, a, [&](long b) {
    auto at = [&](int m) -> double& { return d[b + m * st]; };
    if (hi.type == BcType::Periodic) {
      for (int m = 0; m <= kGhost; ++m) at(n + m) = at(m);
      for (int m = 1; m <= kGhost; ++m) at(-m) = at(n - m);
      return;
    }
    if (lo.type == BcType::Wall) {
      const double uw = lo.wall_velocity[a];
      at(0) = uw;
      for (int m = 1; m <= kGhost; ++m) at(-m) = 2 * uw - at(m);
    } else {
      for (int m = 1; m <= kGhost; ++m) at(-m) = at(0);
    }
    if (hi.type == BcType::Wall) {
      const double uw = hi.wall_velocity[a];
      at(n) = uw;
      for (int m = 1; m <= kGhost; ++m) at(n + m) = 2 * uw - at(n - m);
    } else {
      for (int m = 1; m <= kGhost; ++m) at(n + m) = at(n);
    }
  });
}

// Ghosts along axis a of a field that is cell-centred along a (n cells). For a Wall side the
// ghost is 2 w - f (w = wall value of this quantity) when `odd`, a plain mirror otherwise;
// for an Open side it is 2 w_open - f when `odd_open`, a mirror otherwise.
void fill_centred(Field& f, int a, int n, const SideBc& lo, const SideBc& hi, double wall_lo,
                  double wall_hi, bool odd_wall, bool odd_open) {
  const long st = f.stride(a);
  double* d = f.data();
  auto ghost = [&](const SideBc& s, double wv, double inner) {
    bool odd = (s.type == BcType::Wall && odd_wall) || (s.type == BcType::Open && odd_open);
    double w = s.type == BcType::Open ? s.pressure : wv;
    return odd ? 2 * w - inner : inner;
  };
  for_each_line(f, a, [&](long b) {
    auto at = [&](int m) -> double& { return d[b + m * st]; };
    if (lo.type == BcType::Periodic) {
      for (int m = 0; m < kGhost; ++m) at(-1 - m) = at(n - 1 - m), at(n + m) = at(m);
      return;
    }
    for (int m = 0; m < kGhost; ++m) {
      at(-1 - m) = ghost(lo, wall_lo, at(m));
      at(n + m) = ghost(hi, wall_hi, at(n - 1 - m));
    }
  });
}

}  // namespace

FluidBoundary uniform_boundary(BcType t) {
  FluidBoundary bc;
  for (auto& s : bc) s.type = t;
  return bc;
}

void validate_boundary(const FluidBoundary& bc) {
  for (int d = 0; d < 3; ++d) {
    bool plo = bc[2 * d].type == BcType::Periodic, phi = bc[2 * d + 1].type == BcType::Periodic;
    if (plo != phi)
      throw Error(fmt::format("fluid boundary: side {} is periodic but side {} is not", side_name(plo ? 2 * d : 2 * d + 1),
                              side_name(plo ? 2 * d + 1 : 2 * d)));
  }
}

std::string describe_boundary(const FluidBoundary& bc) {
  std::string s;
  for (int i = 0; i < 6; ++i) {
    const SideBc& b = bc[i];
    if (b.type == BcType::Wall)
      s += fmt::format("{}: wall U_w = ({}, {}, {}) m/s; ", side_name(i), b.wall_velocity.x, b.wall_velocity.y,
                       b.wall_velocity.z);
    else if (b.type == BcType::Open)
      s += fmt::format("{}: open p = {} Pa; ", side_name(i), b.pressure);
    else
      s += fmt::format("{}: periodic; ", side_name(i));
  }
  return s;
}

std::array<int, 2> active_face_range(const MacGrid& g, const FluidBoundary& bc, int d) {
  const int n = g.n()[d];
  const BcType lo = bc[2 * d].type, hi = bc[2 * d + 1].type;
  if (lo == BcType::Periodic) return {0, n};
  return {lo == BcType::Wall ? 1 : 0, hi == BcType::Wall ? n : n + 1};
}

void fill_velocity_component_ghosts(const MacGrid& g, const FluidBoundary& bc, int d, Field& f) {
  const std::array<int, 3> n = g.n();
  for (int a = 0; a < 3; ++a) {
    const SideBc &lo = bc[2 * a], &hi = bc[2 * a + 1];
    if (a == d)
      fill_normal(f, a, n[a], lo, hi);
    else
      fill_centred(f, a, n[a], lo, hi, lo.wall_velocity[d], hi.wall_velocity[d], true, false);
  }
}

void fill_velocity_ghosts(const MacGrid& g, const FluidBoundary& bc, Field& u, Field& v, Field& w) {
  fill_velocity_component_ghosts(g, bc, 0, u);
  fill_velocity_component_ghosts(g, bc, 1, v);
  fill_velocity_component_ghosts(g, bc, 2, w);
}

void fill_scalar_ghosts(const MacGrid& g, const FluidBoundary& bc, Field& s, ScalarKind kind) {
  const std::array<int, 3> n = g.n();
  for (int a = 0; a < 3; ++a)
    fill_centred(s, a, n[a], bc[2 * a], bc[2 * a + 1], 0.0, 0.0, false, kind == ScalarKind::Pressure);
}

}  // namespace cgdem::fluid
