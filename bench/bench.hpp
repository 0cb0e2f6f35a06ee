// Benchmarks reachable from the command line (`cgdem bench ...`). They print figures and
// never pass or fail on time; the last line of each is "<name>: <number>".
#pragma once
#include <string>

namespace cgdem::bench {

// Dense-bed DEM benchmark (shared/bench/dem_bed/README.md).
struct DemBenchArgs {
  std::string bed;       // CSV x,y,z,d in metres
  long steps = 2000;
  int threads = 1;
  // Run the stripped reference of the same law (bench/dem/stripped_dem.hpp) instead of
  // the engine: one thread, a bound on what the engine can reach on this machine.
  bool stripped = false;
  bool accounts = false;  // the stripped reference keeps the energy accounts too
  bool no_accounts = false;  // the engine runs without its energy accounts (output.energy_accounts = false)
  // The contact law (a row of contact/laws.hpp) with its default material; the linear
  // law's is the paper's Table 1.
  std::string law = "linear";
  // The box's inner lengths along x and y [m] (walls at 0 and there; floor at z = 0): the
  // shared beds' 0.010 x 0.006 m, or that of a bed tiled from them (bench/dem/tile_bed.py).
  double box_x = 0.010, box_y = 0.006;
  // Rebuild the neighbour lists every this many steps whether or not the particles moved
  // (0: only when the rebuild test asks, as in a run). A settled bed never asks; the
  // powder pouring into the die (Case 1-1) asks every 12-14 steps, and this puts the
  // build's cost at that size on the bench. Not with --stripped (which never rebuilds).
  long rebuild_every = 0;
};
int run_dem_bench(const DemBenchArgs& args);

// Pressure solve on the die-filling grid with a packed-bed coefficient field.
struct PressureBenchArgs {
  int nx = 140, ny = 70, nz = 50;
  int threads = 2;
  int repeats = 5;
  bool with_cholmod = true;   // the direct solve is slow (~30 s): can be switched off
};
int run_pressure_bench(const PressureBenchArgs& args);

// One full air step (bench/fluid) on the die-filling grid: packed bed, Ergun K, moving shoe.
struct FluidBenchArgs {
  int nx = 140, ny = 70, nz = 50;
  int threads = 2;
  int steps = 10;                  // timed steps
  int warmup = 3;                  // untimed steps before (projection of the initial field)
  int time_order = 2;              // 1: Euler, 2: Heun (two projected stages)
  std::string method = "pcg-mg2";  // pressure solver
  double tolerance = 1e-8;         // relative residual of the pressure solves
  double stage_tolerance = -1;     // of the Heun stage-1 solve (-1: the solver's default)
};
int run_fluid_bench(const FluidBenchArgs& args);

}  // namespace cgdem::bench
