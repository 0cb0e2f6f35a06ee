// Data exchanged between the air solver and its callers (coupling, die filling, tests).
//
//   FluidState   the air at one instant: MAC velocities u, v, w [m/s], pressure p [Pa] at
//                cell centres, void fraction eps (at the END of the coming step) and eps_old
//                (at its start); the caller supplies both, so d(eps)/dt = (eps - eps_old)/dt
//                is exactly the one the continuity equation (eq. 12) sees.
//   FluidParams  material constants, boundary conditions, numerical options.
//   Sources      momentum exchange with the particles, per velocity face (eq. 13 term -f):
//                air momentum source = f_explicit + Kv - K u, with K >= 0 [kg m^-3 s^-1]
//                treated implicitly (semi-implicit drag: K = beta on the face, Kv = beta v_p).
//                An empty Field means "absent".
//   StepStats    what one step did.
#pragma once
#include <array>

#include "fluid/boundary.hpp"
#include "fluid/mac_grid.hpp"
#include "fluid/momentum_terms.hpp"
#include "fluid/pressure_options.hpp"

namespace cgdem::fluid {

struct FluidState {
  MacGrid grid;
  Field u, v, w;      // [m/s] on x-, y-, z-faces
  Field p;            // [Pa] cell centres (the full pressure, not an increment)
  Field eps, eps_old; // void fraction, cell centres, in (0, 1]
  double t = 0;       // [s]

  Field& vel(int d) { return d == 0 ? u : (d == 1 ? v : w); }
  const Field& vel(int d) const { return d == 0 ? u : (d == 1 ? v : w); }
};

// Zero velocity and pressure, eps = eps_old = 1 (pure air).
FluidState make_fluid_state(const MacGrid& g);

struct FluidParams {
  double rho = 1.0;      // [kg/m^3]
  double mu = 1.8e-5;    // [Pa s]
  Vec3 gravity{};        // [m/s^2]
  FluidBoundary bc{};    // six sides (boundary.hpp)
  pressure::SolverOptions pressure{};
  // Relative tolerance of the stage-1 (predictor) solve of Heun's method (0: pressure.rel_tol).
  // u^(1) enters the step only through R(u^(1)) dt/2, and the final solve (pressure.rel_tol)
  // projects the end-of-step velocity, so this loosens no constraint (docs/air_discretization.md).
  double stage_rel_tol = 1e-4;
  Advection advection = Advection::VanLeer;
  int time_order = 2;    // 1: forward Euler, 2: Heun (two projected stages)
  int ibm_samples = 4;   // n of the n^3 sub-samples for alpha
  double cfl = 0.5;      // advective Courant number sum_d |u_d| dt / dx
  double visc_safety = 0.8;  // fraction of the explicit viscous limit dx^2 rho / (6 mu)
  double dt_max = 1e30;  // [s]

  void validate() const;
};

struct Sources {
  std::array<Field, 3> K;           // implicit coefficient [kg m^-3 s^-1] per d-face
  std::array<Field, 3> Kv;          // K v_p [N/m^3] per d-face
  std::array<Field, 3> f_explicit;  // any other force density [N/m^3] per d-face
  Field mass;  // [1/s] cells: added to d(eps)/dt + div(E u) of the continuity, which then
               // reads d(eps)/dt + div(E u) + mass = 0 (a volume the solid or the walls
               // displace beyond what eps shows: coupling/exchange.hpp, porosity_source)
};

struct StepStats {
  int pressure_iterations = 0;   // summed over the stages of the step
  int stage_iterations = 0;      // of them, in the stage-1 solve (time_order 2)
  double pressure_residual = 0;  // relative residual of the last solve
  bool pressure_converged = true;
  double max_divergence = 0;     // max_c |d(eps)/dt + div(eps u)| [1/s] after the step, over
                                 // the cells with fluid (alpha_cell < 1)
  double max_divergence_walls = 0;  // the same over the cells entirely inside walls (not imposed)
  double cfl = 0;                // sum_d max|u_d| dt / dx after the step
  bool ibm_updated = false;
};

}  // namespace cgdem::fluid
