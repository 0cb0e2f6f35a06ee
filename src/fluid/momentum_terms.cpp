// No floating-point contraction: the AVX2 and AVX-512 builds of the sweep (which have FMA)
// compute the same bits as the baseline one.
#pragma GCC optimize("fp-contract=off")
#include "fluid/momentum_terms.hpp"

#include "core/select.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace cgdem::fluid {

namespace {

// Read-only view of a Field: element (i, j, k) at o[i + sy j + sz k].
struct View {
  const double* o;
  long sy, sz;
  explicit View(const Field& f) : o(f.data() + f.index(0, 0, 0)), sy(f.stride(1)), sz(f.stride(2)) {}
  long step(int e) const { return e == 0 ? 1 : (e == 1 ? sy : sz); }
  long at(long i, long j, long k) const { return i + sy * j + sz * k; }
  // Address of element (i, j, k).
  const double* ptr(long i, long j, long k) const { return o + at(i, j, k); }
};

// std::fmin(x, y) as the C library of this platform computes it for quiet operands (glibc,
// x86-64: minsd when ordered, x < y ? x : y; otherwise the operand that is not NaN, x when
// both are), written as a select: a loop of it vectorizes, where std::fmin is a call. The
// operands here are magnitudes, never -0, so equal operands are the same bits.
inline double fmin_select(double x, double y) { return select((x < y) | (y != y), x, y); }

// The limiter psi(a, b). The TVD ones evaluate their formula for every element and then
// select it or 0 (where a b <= 0): the value a branch would give, with no branch in the
// loops that call them.
template <Advection S>
inline double limited_slope(double a, double b) {
  if constexpr (S == Advection::Upwind) return 0.0;
  if constexpr (S == Advection::Central) return b;
  if constexpr (S == Advection::VanLeer) {
    const double r = 2 * a * b / (a + b);
    return select(a * b > 0, r, 0.0);
  }
  if constexpr (S == Advection::MC) {
    const double r =
        std::copysign(fmin_select(fmin_select(2 * std::fabs(a), 0.5 * std::fabs(a + b)), 2 * std::fabs(b)), b);
    return select(a * b <= 0, 0.0, r);
  }
  return 0.0;
}

// The two momentum fluxes through the upper e-side of the control volume of a d-face, for a
// row of n consecutive faces (i .. i+n-1, j, k) of component D at a time. Each row function
// is a plain loop over the row with no branch (upwind side, limiter and e == D resolved by
// selects and template arguments), so that it vectorizes; element m is computed with the
// same operations, in the same order, as the formula for that single face.
struct Kernel {
  double rho, mu, inv_dx;
  View ud, ec;
  std::array<View, 3> v, E;

  // Advective flux  M_e q_e  at the upper e-sides of the row. Reads eps_e u_e at the two
  // e-faces above each face (the mass flux M_e) and u_D at the four faces idx - e .. idx + 2e
  // (both reconstructions q, one from each side); writes out[0 .. n).
  template <Advection S, int D, int e>
  [[gnu::always_inline]] void adv_row(long i, long j, long k, long n, double* __restrict out) const {
    const View &ve = v[e], &epe = E[e];
    const long a = ve.at(i, j, k) + ve.step(e), b = a - ve.step(D);
    const double *va = ve.o + a, *vb = ve.o + b, *ea = epe.o + a, *eb = epe.o + b;
    const long s = ud.step(e);
    const double* u0 = ud.ptr(i, j, k);
    const double *um = u0 - s, *u1 = u0 + s, *u2 = u0 + 2 * s;
    const double r = rho;
#pragma GCC ivdep
    for (long m = 0; m < n; ++m) {
      const double mass = 0.5 * r * (ea[m] * va[m] + eb[m] * vb[m]);
      const double q_lo = u0[m] + 0.5 * limited_slope<S>(u0[m] - um[m], u1[m] - u0[m]);  // from below (M >= 0)
      const double q_hi = u1[m] + 0.5 * limited_slope<S>(u1[m] - u2[m], u0[m] - u1[m]);  // from above
      out[m] = mass * select(mass >= 0, q_lo, q_hi);
    }
  }

  // Viscous stress at the upper e-sides of the row; writes out[0 .. n).
  //   e == D: T_d at the cell above each face. Reads u_f at both f-faces of that cell
  //           (f = 0, 1, 2; the divergence), u_D at the face and the next one, eps_cell.
  //   e != D: T_e at the edge above each face. Reads eps_cell of the four cells around the
  //           edge, u_D at the face and the next one along e, u_e at the two e-faces above.
  template <int D, int e>
  [[gnu::always_inline]] void stress_row(long i, long j, long k, long n, double* __restrict out) const {
    const double h = inv_dx, m_u = mu;
    const double* u = ud.ptr(i, j, k);
    const double* ep = ec.ptr(i, j, k);
    if constexpr (e == D) {
      const double *w0 = v[0].ptr(i, j, k), *w1 = v[1].ptr(i, j, k), *w2 = v[2].ptr(i, j, k);
      const long s1 = v[1].step(1), s2 = v[2].step(2), sd = ud.step(D);
#pragma GCC ivdep
      for (long m = 0; m < n; ++m) {
        double s = 0;
        s += w0[m + 1] - w0[m];
        s += w1[m + s1] - w1[m];
        s += w2[m + s2] - w2[m];
        const double div_u = s * h;
        out[m] = ep[m] * m_u * (2 * (u[m + sd] - u[m]) * h - (2.0 / 3.0) * div_u);
      }
    } else {
      const double* lo = ep - ec.step(D);
      const long ee = ec.step(e), se = ud.step(e);
      const double* w = v[e].ptr(i, j, k) + v[e].step(e);  // u_e at the e-face above
      const long wd = v[e].step(D);
#pragma GCC ivdep
      for (long m = 0; m < n; ++m) {
        const double eps_edge = 0.25 * (ep[m] + lo[m] + ep[m + ee] + lo[m + ee]);
        const double dud = (u[m + se] - u[m]) * h;
        const double due = (w[m] - w[m - wd]) * h;
        out[m] = eps_edge * m_u * (dud + due);
      }
    }
  }
};

// The flux rows of direction e: advective into fa, viscous into fv (those of the parts on).
template <Advection S, int D, bool Adv, bool Visc, int e>
[[gnu::always_inline]] inline void fluxes(const Kernel& K, long i, long j, long k, long n, double* fa, double* fv) {
  if constexpr (Adv) K.adv_row<S, D, e>(i, j, k, n, fa);
  if constexpr (Visc) K.stress_row<D, e>(i, j, k, n, fv);
}

// One row of the divergence: out[q] (the rhs at the faces of the row) -= the advective and
// += the viscous divergence, from the flux rows: x (n + 1 values, slot 0 the lower side of
// the first face), y and z below (lo) and above (up). The z rows below are overwritten by
// those above, for the next plane. Same sums in the same order as the formula.
template <bool Adv, bool Visc>
[[gnu::always_inline]] inline void divergence_row(long n, double h, const double* __restrict xa,
                                                  const double* __restrict ya_lo, const double* __restrict ya_up,
                                                  double* __restrict za_lo, const double* __restrict za_up,
                                                  const double* __restrict xv, const double* __restrict yv_lo,
                                                  const double* __restrict yv_up, double* __restrict zv_lo,
                                                  const double* __restrict zv_up, double* __restrict out) {
#pragma GCC ivdep
  for (long q = 0; q < n; ++q) {
    if constexpr (Adv) {
      double div = 0;
      div += xa[q + 1] - xa[q];
      div += ya_up[q] - ya_lo[q];
      div += za_up[q] - za_lo[q];
      out[q] -= div * h;
      za_lo[q] = za_up[q];
    }
    if constexpr (Visc) {
      double div = 0;
      div += xv[q + 1] - xv[q];
      div += yv_up[q] - yv_lo[q];
      div += zv_up[q] - zv_lo[q];
      out[q] += div * h;
      zv_lo[q] = zv_up[q];
    }
  }
}

// The planes ka <= k < kb of the range: per row (j, k), first the flux rows (upper sides in
// x, y and z; simple loops that vectorize), then the divergence row. Built for the baseline
// target, AVX2 and AVX-512 (the best one the processor has is called; no contraction, so
// all three give the same bits). Adv / Visc: which parts are computed.
// With spans, a row is evaluated over its span only. The lower y-fluxes of a row (the upper
// ones of the row before) and its lower z-fluxes (its upper ones in the plane below) are
// reused where that row or plane evaluated them, and evaluated afresh elsewhere in the span:
// each flux is a function of its position alone, so either way it has the same bits.
template <Advection S, int D, bool Adv, bool Visc>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void sweep_planes(
    const Kernel& K, const FaceRange& r, int ka, int kb, Field& rhs, const RowSpans* spans) {
  const long i0 = r[0][0], i1 = r[0][1], j0 = r[1][0], j1 = r[1][1];
  const long ni = i1 - i0, nj = j1 - j0;
  // Flux buffers (advective a, viscous v), slot i - i0 for face i: x along the row (slot 0
  // = face i0 - 1, so face i at slot i - i0 + 1), y of the row below and of this row, z of
  // the plane below (per row) and of this row.
  std::vector<double> xa(ni + 1), xv(ni + 1), ya(ni), yv(ni), ya2(ni), yv2(ni), za(ni * nj), zv(ni * nj),
      za2(ni), zv2(ni);
  double *ya_lo = ya.data(), *ya_up = ya2.data(), *yv_lo = yv.data(), *yv_up = yv2.data();
  // Where the buffers hold valid fluxes: ya_lo over [y_lo, y_hi) (of the row before); row
  // j's z buffer over [z_lo[j], z_hi[j]) of plane z_k[j].
  long y_lo = 0, y_hi = 0;
  std::vector<long> z_lo(nj, 0), z_hi(nj, 0), z_k(nj, ka - 1);
  // Fills `have` (valid over [h_lo, h_hi)) up to [lo, hi) with flux rows from `fill(a, b)`.
  auto complete = [](long lo, long hi, long h_lo, long h_hi, auto&& fill) {
    if (h_hi <= h_lo || h_hi <= lo || hi <= h_lo) return fill(lo, hi);
    if (lo < h_lo) fill(lo, h_lo);
    if (h_hi < hi) fill(h_hi, hi);
  };
  for (int k = ka; k < kb; ++k) {
    double* out = rhs.data() + rhs.index(0, 0, k);
    y_lo = y_hi = 0;
    for (long j = j0; j < j1; ++j) {
      const auto [lo, hi] = row_span(spans, r, j, k);
      const long n = hi - lo, o = lo - i0;
      if (n <= 0) {
        y_lo = y_hi = 0;
        continue;
      }
      double *za_lo = za.data() + (j - j0) * ni, *zv_lo = zv.data() + (j - j0) * ni;
      const bool z_fresh = z_k[j - j0] == k - 1;
      complete(lo, hi, z_fresh ? z_lo[j - j0] : 0, z_fresh ? z_hi[j - j0] : 0, [&](long a, long b) {
        fluxes<S, D, Adv, Visc, 2>(K, a, j, k - 1, b - a, za_lo + (a - i0), zv_lo + (a - i0));
      });
      complete(lo, hi, y_lo, y_hi, [&](long a, long b) {
        fluxes<S, D, Adv, Visc, 1>(K, a, j - 1, k, b - a, ya_lo + (a - i0), yv_lo + (a - i0));
      });
      fluxes<S, D, Adv, Visc, 0>(K, lo - 1, j, k, n + 1, xa.data() + o, xv.data() + o);
      fluxes<S, D, Adv, Visc, 1>(K, lo, j, k, n, ya_up + o, yv_up + o);
      fluxes<S, D, Adv, Visc, 2>(K, lo, j, k, n, za2.data() + o, zv2.data() + o);
      divergence_row<Adv, Visc>(n, K.inv_dx, xa.data() + o, ya_lo + o, ya_up + o, za_lo + o, za2.data() + o,
                                xv.data() + o, yv_lo + o, yv_up + o, zv_lo + o, zv2.data() + o,
                                out + rhs.stride(1) * j + lo);
      z_lo[j - j0] = lo, z_hi[j - j0] = hi, z_k[j - j0] = k;
      std::swap(ya_lo, ya_up);  // this row's upper y-fluxes are the next row's lower ones
      std::swap(yv_lo, yv_up);
      y_lo = lo, y_hi = hi;
    }
  }
}

// OpenMP splits the planes into contiguous chunks, one per thread. The chunk is a call of
// sweep_planes from inside the parallel region: GCC outlines the region's body before it
// makes the target clones, so a loop written in the region itself would only be built for
// the baseline target.
template <Advection S, int D, bool Adv, bool Visc>
void sweep(const Kernel& K, const FaceRange& r, Field& rhs, const RowSpans* spans) {
  const int i0 = r[0][0], i1 = r[0][1], j0 = r[1][0], j1 = r[1][1], k0 = r[2][0], k1 = r[2][1];
  if (i1 <= i0 || j1 <= j0 || k1 <= k0) return;
  const long ni = i1 - i0, nj = j1 - j0, nk = k1 - k0;
  const bool par = ni * nj * nk > kOmpMinWork;
#pragma omp parallel if (par)
  {
    const auto [ka, kb] = plane_chunk(spans, k0, static_cast<int>(nk), omp_get_thread_num(), omp_get_num_threads());
    if (ka < kb) sweep_planes<S, D, Adv, Visc>(K, r, ka, kb, rhs, spans);
  }
}

}  // namespace

std::array<int, 2> plane_chunk(const RowSpans* spans, int k0, int nk, int t, int nth) {
  // The plane count before thread u's chunk: equal counts, or the first count whose work
  // reaches the share of the threads before u.
  auto bound = [&](int u) {
    if (u >= nth) return nk;
    if (!spans) return static_cast<int>(static_cast<long>(nk) * u / nth);
    const long want = (spans->work[nk] * u + nth - 1) / nth;
    return static_cast<int>(std::lower_bound(spans->work, spans->work + nk + 1, want) - spans->work);
  };
  return {k0 + bound(t), k0 + bound(t + 1)};
}

Advection advection_from_string(const std::string& name) {
  if (name == "upwind") return Advection::Upwind;
  if (name == "central") return Advection::Central;
  if (name == "van-leer") return Advection::VanLeer;
  if (name == "mc") return Advection::MC;
  throw Error("unknown advection scheme '" + name + "' (expected upwind, central, van-leer or mc)");
}

void add_momentum_terms(const MacGrid& g, int d, bool advect, Advection scheme, double rho, double mu,
                        const std::array<const Field*, 3>& vel, const std::array<const Field*, 3>& eps_face,
                        const Field& eps_cell, const FaceRange& range, Field& rhs, const RowSpans* spans) {
  const bool visc = mu > 0;
  if (!advect && !visc) return;
  const Field& dummy = *vel[d];
  auto view_or = [&](const Field* f) { return View(f ? *f : dummy); };
  Kernel K{rho,
           mu,
           1.0 / g.dx,
           View(*vel[d]),
           View(visc ? eps_cell : dummy),
           {View(*vel[0]), View(*vel[1]), View(*vel[2])},
           {view_or(eps_face[0]), view_or(eps_face[1]), view_or(eps_face[2])}};
  // The component d, the flux direction e, the scheme and which parts are computed are
  // template arguments: strides, the e == d branch, the limiter and the part switches are
  // resolved at compile time (same arithmetic).
  auto run = [&]<Advection S, bool Adv, bool Visc>() {
    if (d == 0) sweep<S, 0, Adv, Visc>(K, range, rhs, spans);
    else if (d == 1) sweep<S, 1, Adv, Visc>(K, range, rhs, spans);
    else sweep<S, 2, Adv, Visc>(K, range, rhs, spans);
  };
  auto with_parts = [&]<Advection S>() {
    if (visc) run.template operator()<S, true, true>();
    else run.template operator()<S, true, false>();
  };
  if (!advect) {  // viscous part only: the scheme plays no part
    run.template operator()<Advection::Upwind, false, true>();
    return;
  }
  switch (scheme) {
    case Advection::Upwind: with_parts.template operator()<Advection::Upwind>(); break;
    case Advection::Central: with_parts.template operator()<Advection::Central>(); break;
    case Advection::VanLeer: with_parts.template operator()<Advection::VanLeer>(); break;
    case Advection::MC: with_parts.template operator()<Advection::MC>(); break;
  }
}

void add_advection(const MacGrid& g, int d, Advection scheme, double rho, const std::array<const Field*, 3>& vel,
                   const std::array<const Field*, 3>& eps_face, const FaceRange& range, Field& rhs) {
  add_momentum_terms(g, d, true, scheme, rho, 0.0, vel, eps_face, *vel[d], range, rhs);
}

void add_viscous(const MacGrid& g, int d, double mu, const std::array<const Field*, 3>& vel, const Field& eps_cell,
                 const FaceRange& range, Field& rhs) {
  add_momentum_terms(g, d, false, Advection::Upwind, 0.0, mu, vel, {nullptr, nullptr, nullptr}, eps_cell, range, rhs);
}

}  // namespace cgdem::fluid
