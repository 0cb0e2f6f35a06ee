// Particle <-> air exchange of the coupled method (paper eqs. 8-11, 14), all through the
// one TSC kernel of kernel.hpp:
//
//   void fraction   V_s(c) = sum_p w_c(x_p) V_p,   eps(c) = max(eps_min, 1 - V_s(c)/dx^3)
//                   (sum_c V_s(c) = sum_p V_p exactly; cells clipped at eps_min are counted)
//   air at parcel   u_f(x_p) = sum_f w_f(x_p) u(f) per component on its face lattice,
//                   eps(x_p) likewise from the cells, grad p(x_p) from the face gradients
//                   (p(c) - p(c-1))/dx
//   parcel forces   drag   c_p = V_p beta/(1-eps)(eps(x_p), |u_f - v_p|, d_O)   eq. (8)
//                   F_D = c_p (u_f - v_p)   (integrated implicitly by DemSolver::kick)
//                   f_ext = -V_p grad p(x_p)
//   air reaction    K(f)  = sum_p w_f(x_p) c_p / dx^3,   Kv(f) = sum_p w_f(x_p) c_p vbar_p / dx^3
//                   so that the air feels -f = K (vbar - u) per volume (eq. 14, implicit in
//                   u); vbar_p = Particles::v_avg, the parcel's mean velocity over the step.
//
// Because interpolation and deposit use the same weights, the drag the air receives is
// minus the sum of what the parcels receive (up to the change of u over one fluid step).
// Deposits run serially in particle order (deterministic); gathers run in parallel.
#pragma once
#include <vector>

#include "coupling/drag.hpp"
#include "coupling/kernel.hpp"
#include "fluid/fluid_state.hpp"
#include "particles/particles.hpp"
#include "particles/species.hpp"

namespace cgdem::coupling {

struct ExchangeParams {
  DragLaw law = DragLaw::ErgunWenYu;
  AirProperties air;
  double eps_min = 0.2;                         // lower bound of the mapped void fraction
  fluid::FluidBoundary bc{};                    // of the air (periodic axes, pressure ghosts)
};

struct VoidStats {
  double parcel_volume = 0;   // sum of V_p of the parcels mapped [m^3]
  double grid_volume = 0;     // sum over cells of V_s before clipping [m^3]
  long clipped_cells = 0;     // cells where 1 - V_s/dx^3 < eps_min
  double eps_min_raw = 1;     // smallest 1 - V_s/dx^3 before clipping
};

class Exchange {
 public:
  Exchange(const fluid::MacGrid& g, const std::vector<Species>& species, ExchangeParams params);

  // eps from the parcel positions (writes every interior cell of eps).
  VoidStats void_fraction(const Particles& p, fluid::Field& eps) const;
  // Sets p.u_fluid, p.drag and p.f_ext from the air state (u, p, eps of `air`).
  void air_to_parcels(const fluid::FluidState& air, Particles& p) const;
  // K and Kv of src (resized to the face layout) from p.drag and p.v_avg.
  void parcels_to_air(const Particles& p, fluid::Sources& src) const;

  const ExchangeParams& params() const { return params_; }
  const std::array<bool, 3>& periodic() const { return periodic_; }

 private:
  fluid::MacGrid g_;
  ExchangeParams params_;
  std::array<bool, 3> periodic_{};
  std::vector<double> volume_, d_original_;  // per species
  Lattice cells_;
  std::array<Lattice, 3> faces_;
};

}  // namespace cgdem::coupling
