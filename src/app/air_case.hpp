// The [air] section of a case: the air phase and its coupling to the parcels. A case
// without [air] (or with air.enabled = false) runs in vacuum, so the effect of the air can
// be isolated by switching one key.
//
//   [air]
//   enabled = true            # false: the same case without air
//   dx = 0.6e-3               # m, (0, 1], cubic cells; the domain must be a whole number of
//                             # cells, at most 1e5 along an axis and 1e8 in all
//   density = 1.0             # kg/m^3, (0, 1e4]
//   viscosity = 1.8e-5        # Pa s, (0, 100]
//   dt_max = 1e-4             # s, (0, 1], largest fluid step (also limited by CFL and
//                             # viscosity); a whole number of DEM steps
//   cfl = 0.5
//   time_order = 2            # 1: forward Euler predictor, 2: Heun
//   drag = "ergun-wen-yu"     # eqs. 9-11 with the original diameter; the others: coupling/drag.hpp (kDragLaws)
//   eps_min = 0.2             # lower bound of the mapped void fraction
//   wall_porosity = "packing" # cells next to walls: the porosity of the packing the parcels
//                             # form (coupling/exchange.hpp); "cell": 1 - V_s/dx^3 of the
//                             # whole cell, walls counted as void (before 4 December 2026)
//   feedback = true           # false: one-way coupling (the air ignores the parcels)
//   coupling = "semi-implicit" # drag coefficient frozen at the start of the step; "implicit":
//                             # at the step's end velocity, solved with the air by KINSOL
//                             # (solvers/coupled/implicit_drag.hpp; one process only)
//   ibm_samples = 4           # n^3 sub-samples per cell for the wall fraction alpha
//   [air.pressure]  method = "pcg-mgw3" (fastest on the die-filling grid: docs/pressure.md),
//                   krylov = "sundials" (SUNDIALS PCG; "fused": the same recurrence, fewer passes),
//                   tolerance = 1e-8 (in (0, 1)), max_iterations = 500 (1 .. 1e6),
//                   stage_tolerance = 1e-4 (in (0, 1); the Heun stage-1 solve, time_order = 2),
//                   mpi_preconditioner = "auto" | "as-mg2" | "as-mg" | "bj-mg" | "bj-mg2" |
//                   "bj-fft" | "pfmg" | "none" (under mpirun only; "auto": as-mg2 on up to
//                   4 ranks, pfmg beyond when built with hypre; docs/scale_out.md)
//   [air.implicit]  (coupling = "implicit") method = "anderson" (KINSOL fixed point with
//                   Anderson acceleration) | "newton" (KINSOL Newton-SPGMR), tolerance = 1e-5
//                   (m/s, in (0, 1]: max |G(u) - u| over the faces), max_iterations = 30
//                   (1 .. 1000), depth = 1 (Anderson depth, 0 .. 20; docs/coupling.md
//                   says why 1)
//   [air.boundary]  x_min = "wall" | "open" | "periodic", x_max, y_min, y_max, z_min,
//                   z_max (default: walls, z_max open); open_pressure = 0.0 (Pa, |p| <= 1e7),
//                   the still air's pressure on the top plane: a lower open side adds the
//                   weight of the air above it; an open side must be normal to gravity
#pragma once
#include "core/config.hpp"
#include "coupling/exchange.hpp"
#include "solvers/coupled/coupled_solver.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

struct AirCase {
  bool enabled = false;
  fluid::MacGrid grid;
  fluid::FluidParams fluid;
  CoupledParams coupled;
  coupling::ExchangeParams exchange;
  // Preconditioner of the distributed pressure solve under mpirun (solvers/pressure_mpi/dist_pressure.hpp):
  // "auto" = "as-mg2" on up to 4 ranks, "pfmg" (hypre) beyond when the build has it.
  std::string mpi_preconditioner = "auto";
};

// Reads [air] (if present) against the DEM domain, time step and gravity.
AirCase read_air_case(Config& cfg, const DemParams& dem);

}  // namespace cgdem::app
