// Single-phase air cases run by `cgdem run` (no particles): a case file with a [flow]
// section instead of [particles]. Used by the convergence studies (`cgdem converge`,
// docs/convergence.md) as the smallest problems with an exact solution.
//
// kind = "taylor_green": the periodic 2-D Taylor-Green vortex in a box [0, L]^2 (a one-cell
// periodic slab in z, all six sides periodic), rho and mu constant, no gravity. With
// k = 2 pi / L and nu = mu / rho the exact solution (fluid/taylor_green.hpp) is
//   u = U0 sin(kx) cos(ky) F,  v = -U0 cos(kx) sin(ky) F,  F(t) = exp(-2 nu k^2 t),
//   mean kinetic energy density  KE(t) = rho U0^2 F^2 / 4.
// The air solver (solvers/fluid/fluid_solver.hpp) starts from the exact field sampled at
// the faces and takes steps of one fixed dt to t = end.
//
//   [flow]
//   kind = "taylor_green"
//   n = 32                    # cells per side (4 .. 4096)
//   length = 6.283185307179586  # m, L (default 2 pi; at most 1e3)
//   amplitude = 1.0           # m/s, U0 (at most 1e3)
//   density = 1.0             # kg/m^3 (at most 1e4)
//   viscosity = 0.05          # Pa s (dynamic; at most 100)
//   end = 1.0                 # s (at most 1e6)
//   dt = 0.02                 # s, fixed step; end must be a whole number of steps (<= 1e9)
//   cfl = 0.5                 # or (not both): a fraction of the explicit limit dt_lim below,
//                             # dt = end / ceil(end / (cfl dt_lim))
//   time_order = 2            # 1: forward Euler, 2: Heun
//   advection = "van-leer"    # or "mc", "central", "upwind"
//   [flow.pressure]  method = "pcg-fft" | "pcg-mg" | "pcg-mg2" | "cg", tolerance = 1e-11,
//                    max_iterations = 500
//   [output]  dir = "out/taylor_green"
//
// dt must not exceed the explicit limit of the solver,
//   dt_lim = min(dx / (2 U0), dx^2 rho / (6 mu))   (advective Courant number 2 U0 dt/dx = 1,
//                                                   viscous limit of FluidSolver::stable_dt).
// With flow.cfl and the advective limit binding (n <= 64 with the defaults) dt is
// proportional to dx, so a grid study refines space and time together.
//
// The run writes config.resolved.toml (with the git revision) and metrics.csv:
//   u_error_l2_m_s      rms over the faces of both components of u - u_exact(end)
//   u_error_max_m_s     max of |u - u_exact(end)| over the faces
//   kinetic_energy_J_m3  KE = rho/2 mean(u^2 + v^2) (each component on its n^2 faces)
//   kinetic_energy_rel_error  (KE - KE_exact) / KE_exact, signed
//   decay_factor        A = <u, u_1> / (U0 <u_1, u_1>), u_1 the exact field at F = 1 on the
//                       faces: the amplitude of the vortex mode (a linear functional of u)
//   decay_factor_error  A - F(end), signed
//   max_divergence_1_s, dx_m, dt_s, steps, end_time_s, wall_time_s
#pragma once
#include <string>

#include "core/config.hpp"
#include "fluid/fluid_state.hpp"

namespace cgdem::app {

struct FlowCase {
  std::string kind = "taylor_green";
  int n = 32;
  double length = 0, amplitude = 0;  // [m], [m/s]
  double t_end = 0, dt = 0;          // [s]; dt resolved from flow.dt or flow.cfl
  long steps = 0;
  fluid::MacGrid grid;
  fluid::FluidParams fluid;
  std::string output_dir;
};

// True when the case file describes a flow case ([flow] section).
bool is_flow_case(Config& cfg);

// Reads [flow] and [output]. Throws ConfigError naming the key on bad input.
FlowCase read_flow_case(Config& cfg);

// Runs the case and writes its output folder. Returns the process exit code.
int run_flow_case(const FlowCase& c, const std::string& case_file, const std::string& resolved_config);

}  // namespace cgdem::app
