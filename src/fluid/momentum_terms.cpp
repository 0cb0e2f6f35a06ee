#include "fluid/momentum_terms.hpp"

#include <cmath>
#include <string>

namespace cgdem::fluid {

namespace {

using Idx = std::array<int, 3>;

inline Idx add(Idx a, const Idx& b, int s = 1) {
  for (int q = 0; q < 3; ++q) a[q] += s * b[q];
  return a;
}
inline double at(const Field& f, const Idx& i) { return f(i[0], i[1], i[2]); }

inline double limited_slope(Advection s, double a, double b) {
  switch (s) {
    case Advection::Upwind: return 0.0;
    case Advection::Central: return b;
    case Advection::VanLeer: return a * b > 0 ? 2 * a * b / (a + b) : 0.0;
    case Advection::MC:
      if (a * b <= 0) return 0.0;
      return std::copysign(std::fmin(std::fmin(2 * std::fabs(a), 0.5 * std::fabs(a + b)), 2 * std::fabs(b)), b);
  }
  return 0.0;
}

// Advected value at the upper e-side of idx: upwind-biased TVD reconstruction.
inline double advected(Advection s, const Field& ud, const Idx& idx, const Idx& e, double mass) {
  double um = at(ud, add(idx, e, -1)), u0 = at(ud, idx), u1 = at(ud, add(idx, e)), u2 = at(ud, add(idx, e, 2));
  if (mass >= 0) return u0 + 0.5 * limited_slope(s, u0 - um, u1 - u0);
  return u1 + 0.5 * limited_slope(s, u1 - u2, u0 - u1);
}

template <class Fn>
void for_faces(const FaceRange& r, Fn fn) {
#pragma omp parallel for schedule(static) if (long(r[0][1] - r[0][0]) * (r[1][1] - r[1][0]) * (r[2][1] - r[2][0]) > kOmpMinWork)
  for (int k = r[2][0]; k < r[2][1]; ++k)
    for (int j = r[1][0]; j < r[1][1]; ++j)
      for (int i = r[0][0]; i < r[0][1]; ++i) fn(Idx{i, j, k});
}

}  // namespace

Advection advection_from_string(const std::string& name) {
  if (name == "upwind") return Advection::Upwind;
  if (name == "central") return Advection::Central;
  if (name == "van-leer") return Advection::VanLeer;
  if (name == "mc") return Advection::MC;
  throw Error("unknown advection scheme '" + name + "' (expected upwind, central, van-leer or mc)");
}

void add_advection(const MacGrid& g, int d, Advection scheme, double rho, const std::array<const Field*, 3>& vel,
                   const std::array<const Field*, 3>& eps_face, const FaceRange& range, Field& rhs) {
  const Field& ud = *vel[d];
  const Idx dd = unit(d);
  const double inv_dx = 1.0 / g.dx;
  // Flux through the upper e-side of the control volume of face idx.
  auto flux = [&](const Idx& idx, int e) {
    const Idx ee = unit(e);
    const Field &ve = *vel[e], &epe = *eps_face[e];
    Idx a = add(idx, ee), b = add(add(idx, dd, -1), ee);
    double mass = 0.5 * rho * (at(epe, a) * at(ve, a) + at(epe, b) * at(ve, b));
    return mass * advected(scheme, ud, idx, ee, mass);
  };
  for_faces(range, [&](const Idx& idx) {
    double div = 0;
    for (int e = 0; e < 3; ++e) div += flux(idx, e) - flux(add(idx, unit(e), -1), e);
    rhs(idx[0], idx[1], idx[2]) -= div * inv_dx;
  });
}

void add_viscous(const MacGrid& g, int d, double mu, const std::array<const Field*, 3>& vel, const Field& eps_cell,
                 const FaceRange& range, Field& rhs) {
  const Field& ud = *vel[d];
  const Idx dd = unit(d);
  const double inv_dx = 1.0 / g.dx;
  auto div_u = [&](const Idx& c) {
    double s = 0;
    for (int e = 0; e < 3; ++e) s += at(*vel[e], add(c, unit(e))) - at(*vel[e], c);
    return s * inv_dx;
  };
  // Stress on the upper e-side of the control volume of face idx.
  auto stress = [&](const Idx& idx, int e) {
    const Idx ee = unit(e);
    if (e == d)
      return at(eps_cell, idx) * mu * (2 * (at(ud, add(idx, dd)) - at(ud, idx)) * inv_dx - (2.0 / 3.0) * div_u(idx));
    const Field& ve = *vel[e];
    Idx lo = add(idx, dd, -1);
    double eps_edge =
        0.25 * (at(eps_cell, idx) + at(eps_cell, lo) + at(eps_cell, add(idx, ee)) + at(eps_cell, add(lo, ee)));
    double dud = (at(ud, add(idx, ee)) - at(ud, idx)) * inv_dx;
    double due = (at(ve, add(idx, ee)) - at(ve, add(lo, ee))) * inv_dx;
    return eps_edge * mu * (dud + due);
  };
  for_faces(range, [&](const Idx& idx) {
    double div = 0;
    for (int e = 0; e < 3; ++e) div += stress(idx, e) - stress(add(idx, unit(e), -1), e);
    rhs(idx[0], idx[1], idx[2]) += div * inv_dx;
  });
}

}  // namespace cgdem::fluid
