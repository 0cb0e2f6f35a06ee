// The coupled DEM-CFD step (paper sections 2-3; docs/model.md, Stability).
//
// One fluid step t^n -> t^{n+1} = t^n + dt_f, dt_f = N dt_DEM:
//   1. air -> parcels   u_f, eps, grad p at every parcel from the air at t^n; the linear
//                       drag coefficient c_p = V beta/(1-eps) (eqs. 8-11, ORIGINAL d_O) and
//                       f_ext = -V grad p, held fixed over the step
//   2. DEM substeps     N velocity-Verlet steps with contacts, walls, gravity, f_ext and the
//                       drag c_p (u_f - v) integrated implicitly in each kick; the drag
//                       impulse J_p each parcel receives is accumulated
//   3. void fraction    eps^{n+1} from the parcel positions at t^{n+1} (kernel mapping,
//                       masked by the wall fractions at t^{n+1}, those the air step uses);
//                       next to walls the porosity of the packing, with the continuity
//                       source that keeps the non-solid volume balanced (exchange.hpp)
//   4. parcels -> air   K = sum w c_p / V_cell, Kv = sum w (c_p u_f - J_p/dt_f) / V_cell (eq. 14)
//   5. air step         volume-averaged NS from eps^n to eps^{n+1} with the drag
//                       K (vbar - u^{n+1}) implicit in u, IBM walls at t^{n+1}  (eqs. 12-13)
//   6. correction       each parcel receives the change of its drag over the step,
//                       a (u^{n+1} - u_f) / (1 + a/m_p), a = dt_f c_p: the drag exchange
//                       conserves momentum where a << m_p and stays bounded where the drag
//                       is stiff; the pressure force lags one step (exchange.hpp says why)
// Both phases treat the drag implicitly, so dt_f may exceed the air's drag relaxation time
// eps rho_f/beta (~1e-5 s in a packed bed) by orders of magnitude.
//
// Variants (for verification and to isolate effects): feedback = false drops step 4 (the
// air does not feel the parcels: one-way); move_particles = false skips step 2 (a fixed
// bed: parcels keep their place and velocity, and still drag the air).
//
// Implicit drag coupling (coupling = Implicit, implicit_drag.hpp): steps 4-6 become
//   4'. vbar_p = u_f - J_p/(dt_f c_p), the parcels' drag-weighted mean velocity of the step
//   5'. u^{n+1} = G(u^{n+1}): the air step of 5 with K, Kv deposited from the coefficient at
//       the end of the step, c_p(eps^{n+1}, |u^{n+1}(x_p) - vbar_p|), solved by KINSOL
//   6'. each parcel receives dt_f c_p (u^{n+1}(x_p) - vbar_p) - J_p, what the air lost less
//       what it was given, with the bounding factor 1/(1 + a/m_p) of step 6
// (the DEM substeps keep the coefficient of t^n: the parcels' side is explicit in u, and the
// correction hands them the implicit drag). One process only for now.
#pragma once
#include <array>

#include "coupling/exchange.hpp"
#include "solvers/coupled/implicit_drag.hpp"
#include "solvers/dem/dem_solver.hpp"
#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem {

// How the drag coefficient of the air step is taken (implicit_drag.hpp).
enum class DragCoupling {
  SemiImplicit,  // c_p frozen at t^n (slip and eps of the start of the step), linear air step
  Implicit,      // c_p at the new slip |u^{n+1} - vbar_p| and eps^{n+1}: u = G(u) by KINSOL
};

struct CoupledParams {
  double dt_fluid_max = 1e-4;  // [s] upper bound of the fluid step (also the CFL limit applies)
  bool feedback = true;        // two-way coupling (the parcels' drag acts on the air)
  bool move_particles = true;  // false: parcels held in place
  DragCoupling coupling = DragCoupling::SemiImplicit;
  ImplicitDragOptions implicit;  // coupling = Implicit
};

struct CoupledStepStats {
  int substeps = 0;
  double dt_fluid = 0;
  coupling::VoidStats void_fraction;
  fluid::StepStats fluid;  // implicit coupling: of the accepted air step, pressure
                           // iterations summed over every air step of the nonlinear solve
  ImplicitDragStats drag;  // implicit coupling only (evaluations = 0 otherwise)
};

class CoupledSolver {
 public:
  // The solvers are owned by the caller and must outlive this object. Maps eps at t^n.
  CoupledSolver(DemSolver& dem, fluid::FluidSolver& fluid, fluid::FluidState& air, coupling::Exchange exchange,
                CoupledParams params);

  CoupledStepStats step();
  double time() const { return dem_.time(); }
  // Substeps of the coming fluid step: the largest N with N dt_DEM <= min(dt_fluid_max, CFL).
  int substeps() const;

  const coupling::VoidStats& last_void_stats() const { return void_stats_; }
  // Kernel capacities next to walls over the steps so far (a restart counts from there):
  // nodes taken from the exchange's cache (static walls, or nothing moved), nodes evaluated.
  std::array<long, 2> capacity_nodes() const { return capacity_nodes_; }
  const coupling::Exchange& exchange() const { return ex_; }
  PhaseTimers& timers() { return timers_; }

 private:
  void advance_particles(int n_sub);
  // Steps 4-5 of the implicit coupling: the air step at the drag of its own end velocity.
  void implicit_air_step(double t_end, CoupledStepStats& st);

  DemSolver& dem_;
  fluid::FluidSolver& fluid_;
  fluid::FluidState& air_;
  coupling::Exchange ex_;
  CoupledParams params_;
  fluid::Sources src_;
  coupling::VoidStats void_stats_;
  std::array<long, 2> capacity_nodes_{};
  // The walls at time t for the exchange's masks and capacities: the air solver's fractions
  // brought to t (one copy, computed once per step).
  void walls_at(double t);
  void weights_at(double t);
  coupling::ParcelWeights w_;
  bool weights_fresh_ = false;
  geometry::Scene::Frame frame_;  // the walls of fluid_.ibm() (the capacities' phi)
  // Step 3's mixture fraction and capacities at t^{n+1} (por_) and the mixture at t^n: the
  // air's continuity source next to walls (coupling/exchange.hpp, "Porosity next to walls").
  coupling::VoidFields por_;
  fluid::Field mix_old_;
  PhaseTimers timers_;
  int t_weights_, t_gather_, t_map_, t_deposit_, t_walls_;
  // Implicit coupling: the solver, the parcels' mean velocities and coefficients, the air
  // at t^n, the unknown vector (all face velocities).
  std::unique_ptr<ImplicitDragSolver> implicit_;
  std::vector<Vec3> vbar_;
  std::vector<double> c_;
  fluid::FluidState air_n_;
  std::vector<double> u_vec_;
};

}  // namespace cgdem
