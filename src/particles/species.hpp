// Particle species: a parcel of coarse-grain ratio l stands for l^3 original particles
// of diameter d_O (paper eqs. 3-5):
//     d = l d_O,   m = l^3 m_O,   I = l^5 I_O = (2/5) m (d/2)^2.
// The "simply large" system of the paper is l = 1 with a large d_O.
#pragma once
#include <numbers>
#include <string>

namespace cgdem {

struct Species {
  std::string name;
  double d_original = 0;  // d_O [m]
  double ratio = 1;       // coarse-grain ratio l (>= 1)
  double density = 0;     // rho_p [kg/m^3]

  double diameter() const { return ratio * d_original; }                    // eq. (3)
  double original_mass() const { return density * std::numbers::pi * d_original * d_original * d_original / 6; }
  double l3() const { return ratio * ratio * ratio; }
  double mass() const { return l3() * original_mass(); }                     // eq. (4)
  double inertia() const { return 0.1 * mass() * diameter() * diameter(); }  // eq. (5)
  double volume() const { return std::numbers::pi * diameter() * diameter() * diameter() / 6; }
};

}  // namespace cgdem
