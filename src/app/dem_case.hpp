// A DEM case read from its TOML file: everything needed to build and run the solver.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "io/h5_options.hpp"
#include "particles/insertion.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

struct ParticleFile {
  std::string path;
  int species = 0;
};

struct OutputSpec {
  std::string dir;
  double energy_interval = 1e-3;    // [s] simulated
  double snapshot_interval = 1e-2;  // [s] simulated
  double progress_interval = 10;    // [s] wall clock, when not on a terminal
  double max_speed = 50;            // [m/s] a faster particle stops the run (blow-up)
  double checkpoint_interval = 1e-2;  // [s] simulated, between checkpoints (checkpoint.bin)
  int compression = io::kDefaultCompression;  // deflate level 0..9 of the HDF5 snapshots
  double tracer_time = 0;           // [s] simulated: the parcels' heights then are the tracer z_start
};

struct DemCase {
  std::vector<Species> species;
  contact::ContactModel material;  // the contact law and its parameters ([contact])
  DemParams dem;
  geometry::Scene scene;
  uint64_t seed = 1;
  std::vector<InsertRegion> inserts;
  std::vector<ParticleFile> files;
  double t_start = 0, t_end = 0;
  OutputSpec output;
};

// Reads and validates every section; throws ConfigError naming file and key.
DemCase read_dem_case(Config& cfg);
// Solver with its particles inserted / loaded at t_start.
std::unique_ptr<DemSolver> build_solver(const DemCase& c, const std::string& case_dir);

}  // namespace cgdem::app
