// The periodic 2-D Taylor-Green vortex, the exact solution the flow cases (`cgdem run` with
// a [flow] section, src/app/flow_case.hpp) and the convergence studies compare with.
//
// In a box [0, L]^2 with rho and mu constant and no gravity, with k = 2 pi / L and
// nu = mu / rho (docs/references.md, Taylor-Green vortex):
//   u = U0 sin(kx) cos(ky) F,  v = -U0 cos(kx) sin(ky) F,  F(t) = exp(-2 nu k^2 t),
//   mean kinetic energy density  KE(t) = rho U0^2 F^2 / 4.
#pragma once
#include <cmath>

#include "core/vec3.hpp"
#include "fluid/fluid_state.hpp"

namespace cgdem::fluid {

struct TaylorGreen {
  double k, u0;  // wave number 2 pi / L [1/m], amplitude U0 [m/s]

  // The velocity components at x for the amplitude factor F [m/s].
  double u(const Vec3& x, double F) const { return u0 * std::sin(k * x.x) * std::cos(k * x.y) * F; }
  double v(const Vec3& x, double F) const { return -u0 * std::cos(k * x.x) * std::sin(k * x.y) * F; }
  // The amplitude factor F(t) = exp(-2 nu k^2 t) for the kinematic viscosity nu [m^2/s].
  double decay(double nu, double t) const { return std::exp(-2 * nu * k * k * t); }
  // The exact mean kinetic energy density rho U0^2 F^2 / 4 [J/m^3].
  double kinetic_energy(double rho, double F) const { return rho * u0 * u0 * F * F / 4; }
};

// Writes the exact field at amplitude factor F into every x- and y-face of s (the images of
// periodic faces included); w and p are left as they are.
void set_taylor_green(FluidState& s, const TaylorGreen& tg, double F);

// The discrete field of s against the exact one at amplitude factor F, over the n^2 distinct
// x- and y-faces of the periodic slab (face n is the image of face 0; s.grid is nx x nx x 1).
struct TaylorGreenErrors {
  double l2 = 0;              // rms of u - u_exact over the faces of both components [m/s]
  double max = 0;             // max |u - u_exact| [m/s]
  double kinetic_energy = 0;  // rho/2 mean(u^2 + v^2), each component on its n^2 faces [J/m^3]
  double decay_factor = 0;    // <u, u_1> / (U0 <u_1, u_1>), u_1 the exact field at F = 1
};
TaylorGreenErrors taylor_green_errors(const FluidState& s, const TaylorGreen& tg, double rho, double F);

}  // namespace cgdem::fluid
