// Fluid-particle drag (paper eqs. 8-11), evaluated with the ORIGINAL particle diameter d_O
// whatever the coarse-grain ratio, so that a parcel of l^3 particles feels l^3 times the
// drag of one of them (docs/model.md, Drag):
//
//   F_D = V beta / (1 - eps) (u_f - v)                                       eq. (8)
//   eps <= 0.8, Ergun:   beta = 150 mu (1-eps)^2 / (eps d_O^2)
//                             + 1.75 (1-eps) rho |v - u_f| / d_O            eq. (9)
//   eps >  0.8, Wen-Yu:  beta = 3/4 C_D eps (1-eps) rho |v - u_f| / d_O eps^-2.65   eq. (10)
//   C_D = 24/Re (1 + 0.15 Re^0.687) (Re <= 1000), 0.44 (Re > 1000),
//   Re = eps rho d_O |v - u_f| / mu                                         eq. (11)
//
// The functions return beta/(1-eps) [kg m^-3 s^-1], finite as eps -> 1 (a lone parcel),
// and exact at zero slip (C_D |slip| -> 24 mu/(eps rho d_O)). V beta/(1-eps) is the
// parcel's linear drag coefficient [kg/s]; the air's implicit coefficient is its sum per
// cell volume (eq. 14).
#pragma once
#include <cmath>
#include <string>

namespace cgdem::coupling {

struct AirProperties {
  double rho = 1.0;    // [kg/m^3]
  double mu = 1.8e-5;  // [Pa s]
};

// Drag coefficient per unit volume of a single sphere in air, times |slip|: C_D |slip|.
inline double cd_times_slip(double eps, double slip, double d_o, const AirProperties& air) {
  const double re = eps * air.rho * d_o * slip / air.mu;  // eq. (11)
  if (re <= 1000) return 24 * air.mu / (eps * air.rho * d_o) * (1 + 0.15 * std::pow(re, 0.687));
  return 0.44 * slip;
}

// beta/(1-eps), Ergun branch, eq. (9).
inline double ergun_beta_over_solid(double eps, double slip, double d_o, const AirProperties& air) {
  return 150 * air.mu * (1 - eps) / (eps * d_o * d_o) + 1.75 * air.rho * slip / d_o;
}

// beta/(1-eps), Wen-Yu branch, eq. (10).
inline double wen_yu_beta_over_solid(double eps, double slip, double d_o, const AirProperties& air) {
  return 0.75 * cd_times_slip(eps, slip, d_o, air) * eps * air.rho / d_o * std::pow(eps, -2.65);
}

enum class DragLaw { ErgunWenYu, WenYu, Ergun };

// beta/(1-eps) of the chosen law (the paper's: Ergun below eps = 0.8, Wen-Yu above).
inline double beta_over_solid(DragLaw law, double eps, double slip, double d_o, const AirProperties& air) {
  switch (law) {
    case DragLaw::Ergun: return ergun_beta_over_solid(eps, slip, d_o, air);
    case DragLaw::WenYu: return wen_yu_beta_over_solid(eps, slip, d_o, air);
    case DragLaw::ErgunWenYu: break;
  }
  return eps <= 0.8 ? ergun_beta_over_solid(eps, slip, d_o, air) : wen_yu_beta_over_solid(eps, slip, d_o, air);
}

// "ergun-wen-yu" | "wen-yu" | "ergun"; throws cgdem::Error otherwise.
DragLaw parse_drag_law(const std::string& name);

}  // namespace cgdem::coupling
