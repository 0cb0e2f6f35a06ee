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
#include <vector>

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

// Di Felice (1994), a single correlation over the whole range of eps with a
// Reynolds-dependent voidage exponent (not one of the paper's laws; an alternative for
// sensitivity studies, `air.drag = "di-felice"`):
//   beta/(1-eps) = 3/4 C_D rho |slip| eps^(2 - chi) / d_O,
//   C_D = (0.63 + 4.8 / sqrt(Re))^2,  chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2),
//   Re = eps rho d_O |slip| / mu as in eq. (11).
// C_D |slip| is evaluated as (0.63 sqrt(|slip|) + 4.8 sqrt(mu / (eps rho d_O)))^2, the same
// number without 0 * inf at zero slip, where chi -> 3.7.
inline double di_felice_beta_over_solid(double eps, double slip, double d_o, const AirProperties& air) {
  const double re = eps * air.rho * d_o * slip / air.mu;
  const double chi = re > 0 ? 3.7 - 0.65 * std::exp(-0.5 * std::pow(1.5 - std::log10(re), 2)) : 3.7;
  const double root = 0.63 * std::sqrt(slip) + 4.8 * std::sqrt(air.mu / (eps * air.rho * d_o));
  return 0.75 * root * root * air.rho / d_o * std::pow(eps, 2 - chi);
}

// beta/(1-eps) of the paper's law: Ergun below eps = 0.8, Wen-Yu above.
inline double ergun_wen_yu_beta_over_solid(double eps, double slip, double d_o, const AirProperties& air) {
  return eps <= 0.8 ? ergun_beta_over_solid(eps, slip, d_o, air) : wen_yu_beta_over_solid(eps, slip, d_o, air);
}

// The drag-law registry: one row per law (its enum value, the name the case files use,
// one line of documentation, the function). The config reader, its error message, the
// docs and the tests take the names from here. Adding a law: a function above, an enum
// value, a row.
enum class DragLaw { ErgunWenYu, WenYu, Ergun, DiFelice };

struct DragLawInfo {
  DragLaw law;
  const char* name;
  const char* doc;
  double (*beta_over_solid)(double eps, double slip, double d_o, const AirProperties& air);
};

inline constexpr DragLawInfo kDragLaws[] = {
    {DragLaw::ErgunWenYu, "ergun-wen-yu", "the paper's: Ergun (eq. 9) at eps <= 0.8, Wen-Yu (eq. 10) above",
     ergun_wen_yu_beta_over_solid},
    {DragLaw::WenYu, "wen-yu", "Wen-Yu (eq. 10) at every eps", wen_yu_beta_over_solid},
    {DragLaw::Ergun, "ergun", "Ergun (eq. 9) at every eps", ergun_beta_over_solid},
    {DragLaw::DiFelice, "di-felice", "Di Felice (1994): one correlation, voidage exponent chi(Re)",
     di_felice_beta_over_solid},
};

// The row of a law (the rows are in enum order; tests/coupling/drag_test.cpp checks it).
inline const DragLawInfo& drag_law_info(DragLaw law) { return kDragLaws[static_cast<int>(law)]; }

// beta/(1-eps) of the chosen law.
inline double beta_over_solid(DragLaw law, double eps, double slip, double d_o, const AirProperties& air) {
  return drag_law_info(law).beta_over_solid(eps, slip, d_o, air);
}

// The registered names, in table order.
std::vector<std::string> drag_law_names();

// The law of a registered name; throws cgdem::Error naming the allowed ones otherwise.
DragLaw parse_drag_law(const std::string& name);

}  // namespace cgdem::coupling
