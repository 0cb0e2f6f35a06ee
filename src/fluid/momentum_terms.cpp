#include "fluid/momentum_terms.hpp"

#include <omp.h>

#include <cmath>
#include <type_traits>
#include <string>
#include <vector>

namespace cgdem::fluid {

namespace {

// Read-only view of a Field: element (i, j, k) at o[i + sy j + sz k].
struct View {
  const double* o;
  long sy, sz;
  explicit View(const Field& f) : o(f.data() + f.index(0, 0, 0)), sy(f.stride(1)), sz(f.stride(2)) {}
  double operator()(long i, long j, long k) const { return o[i + sy * j + sz * k]; }
  long step(int e) const { return e == 0 ? 1 : (e == 1 ? sy : sz); }
  long at(long i, long j, long k) const { return i + sy * j + sz * k; }
};

template <Advection S>
inline double limited_slope(double a, double b) {
  if constexpr (S == Advection::Upwind) return 0.0;
  if constexpr (S == Advection::Central) return b;
  if constexpr (S == Advection::VanLeer) return a * b > 0 ? 2 * a * b / (a + b) : 0.0;
  if constexpr (S == Advection::MC) {
    if (a * b <= 0) return 0.0;
    return std::copysign(std::fmin(std::fmin(2 * std::fabs(a), 0.5 * std::fabs(a + b)), 2 * std::fabs(b)), b);
  }
  return 0.0;
}

// The two momentum fluxes through the upper e-side of the control volume of a d-face.
struct Kernel {
  int d;
  double rho, mu, inv_dx;
  View ud, ec;
  std::array<View, 3> v, E;
  bool advect, visc;

  // Advective flux  M_e q_e  at the upper e-side of face (i, j, k) (component d = D).
  template <Advection S, int D, int e>
  double adv(long i, long j, long k) const {
    constexpr int d = D;
    const View &ve = v[e], &epe = E[e];
    const long a = ve.at(i, j, k) + ve.step(e), b = a - ve.step(d);
    const double mass = 0.5 * rho * (epe.o[a] * ve.o[a] + epe.o[b] * ve.o[b]);
    const long c = ud.at(i, j, k), s = ud.step(e);
    const double um = ud.o[c - s], u0 = ud.o[c], u1 = ud.o[c + s], u2 = ud.o[c + 2 * s];
    const double q = mass >= 0 ? u0 + 0.5 * limited_slope<S>(u0 - um, u1 - u0) : u1 + 0.5 * limited_slope<S>(u1 - u2, u0 - u1);
    return mass * q;
  }
  // Viscous stress at the upper e-side of face (i, j, k) (component d = D).
  template <int D, int e>
  double stress(long i, long j, long k) const {
    constexpr int d = D;
    const long c = ud.at(i, j, k), se = ud.step(e);
    const long ce = ec.at(i, j, k);
    if constexpr (e == d) {
      double s = 0;
      for (int f = 0; f < 3; ++f) {
        const long q = v[f].at(i, j, k);
        s += v[f].o[q + v[f].step(f)] - v[f].o[q];
      }
      const double div_u = s * inv_dx;
      return ec.o[ce] * mu * (2 * (ud.o[c + ud.step(d)] - ud.o[c]) * inv_dx - (2.0 / 3.0) * div_u);
    } else {
    const long lo = ce - ec.step(d), ee = ec.step(e);
    const double eps_edge = 0.25 * (ec.o[ce] + ec.o[lo] + ec.o[ce + ee] + ec.o[lo + ee]);
    const double dud = (ud.o[c + se] - ud.o[c]) * inv_dx;
    const View& ve = v[e];
    const long q = ve.at(i, j, k) + ve.step(e);
    const double due = (ve.o[q] - ve.o[q - ve.step(d)]) * inv_dx;
    return eps_edge * mu * (dud + due);
    }
  }
};

template <Advection S, int D>
void sweep(const Kernel& K, const FaceRange& r, Field& rhs) {
  const int i0 = r[0][0], i1 = r[0][1], j0 = r[1][0], j1 = r[1][1], k0 = r[2][0], k1 = r[2][1];
  if (i1 <= i0 || j1 <= j0 || k1 <= k0) return;
  const long ni = i1 - i0, nj = j1 - j0, nk = k1 - k0;
  const bool par = ni * nj * nk > kOmpMinWork;
#pragma omp parallel if (par)
  {
    const int nth = omp_get_num_threads(), tid = omp_get_thread_num();
    const int ka = k0 + static_cast<int>(nk * tid / nth), kb = k0 + static_cast<int>(nk * (tid + 1) / nth);
    // Buffers of upper-side fluxes: x along the row (index i - i0 + 1, slot 0 = face i0 - 1),
    // y of the previous row, z of the previous plane.
    std::vector<double> xa(ni + 1), xv(ni + 1), ya(ni), yv(ni), za(ni * nj), zv(ni * nj);
    auto upper = [&]<int e>(std::integral_constant<int, e>, long i, long j, long k, double& fa, double& fv) {
      fa = K.advect ? K.template adv<S, D, e>(i, j, k) : 0.0;
      fv = K.visc ? K.template stress<D, e>(i, j, k) : 0.0;
    };
    constexpr std::integral_constant<int, 0> X{};
    constexpr std::integral_constant<int, 1> Y{};
    constexpr std::integral_constant<int, 2> Z{};
    for (int k = ka; k < kb; ++k) {
      if (k == ka)
        for (long j = j0; j < j1; ++j)
          for (long i = i0; i < i1; ++i) upper(Z, i, j, k - 1, za[(j - j0) * ni + i - i0], zv[(j - j0) * ni + i - i0]);
      for (long i = i0; i < i1; ++i) upper(Y, i, j0 - 1, k, ya[i - i0], yv[i - i0]);
      double* out = rhs.data() + rhs.index(0, 0, k);
      for (long j = j0; j < j1; ++j) {
        for (long i = i0 - 1; i < i1; ++i) upper(X, i, j, k, xa[i - i0 + 1], xv[i - i0 + 1]);
        double* ro = out + rhs.stride(1) * j;
        double* zar = za.data() + (j - j0) * ni;
        double* zvr = zv.data() + (j - j0) * ni;
        for (long i = i0; i < i1; ++i) {
          const long q = i - i0;
          double fya, fyv, fza, fzv;
          upper(Y, i, j, k, fya, fyv);
          upper(Z, i, j, k, fza, fzv);
          if (K.advect) {
            double div = 0;
            div += xa[q + 1] - xa[q];
            div += fya - ya[q];
            div += fza - zar[q];
            ro[i] -= div * K.inv_dx;
          }
          if (K.visc) {
            double div = 0;
            div += xv[q + 1] - xv[q];
            div += fyv - yv[q];
            div += fzv - zvr[q];
            ro[i] += div * K.inv_dx;
          }
          ya[q] = fya, yv[q] = fyv, zar[q] = fza, zvr[q] = fzv;
        }
      }
    }
  }
}

}  // namespace

Advection advection_from_string(const std::string& name) {
  if (name == "upwind") return Advection::Upwind;
  if (name == "central") return Advection::Central;
  if (name == "van-leer") return Advection::VanLeer;
  if (name == "mc") return Advection::MC;
  throw Error("unknown advection scheme '" + name + "' (expected upwind, central, van-leer or mc)");
}

void add_momentum_terms(const MacGrid& g, int d, bool advect, Advection scheme, double rho, double mu,
                        const std::array<const Field*, 3>& vel, const std::array<const Field*, 3>& eps_face,
                        const Field& eps_cell, const FaceRange& range, Field& rhs) {
  const bool visc = mu > 0;
  if (!advect && !visc) return;
  const Field& dummy = *vel[d];
  auto view_or = [&](const Field* f) { return View(f ? *f : dummy); };
  Kernel K{d,
           rho,
           mu,
           1.0 / g.dx,
           View(*vel[d]),
           View(visc ? eps_cell : dummy),
           {View(*vel[0]), View(*vel[1]), View(*vel[2])},
           {view_or(eps_face[0]), view_or(eps_face[1]), view_or(eps_face[2])},
           advect,
           visc};
  // The component d and the flux direction e are template arguments: the strides and the
  // e == d branch are resolved at compile time (same arithmetic).
  auto run = [&]<Advection S>() {
    if (d == 0) sweep<S, 0>(K, range, rhs);
    else if (d == 1) sweep<S, 1>(K, range, rhs);
    else sweep<S, 2>(K, range, rhs);
  };
  switch (scheme) {
    case Advection::Upwind: run.template operator()<Advection::Upwind>(); break;
    case Advection::Central: run.template operator()<Advection::Central>(); break;
    case Advection::VanLeer: run.template operator()<Advection::VanLeer>(); break;
    case Advection::MC: run.template operator()<Advection::MC>(); break;
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
