// Checkpoints of a run: `<output>/checkpoint.bin`, written atomically at every
// output.checkpoint_interval of simulated time (after the health checks passed) and at the
// end. It holds the complete state — DEM (particles, neighbour lists with contact history,
// counters), air (velocities, pressure, eps at both ends of the step, time), diagnostics
// (impacts, mass history) and the run's counters — so that `cgdem run CASE --restart
// <output>/checkpoint.bin` continues bit-identically to a run that never stopped. The
// moving walls need no state of their own: their position is a function of time.
#pragma once
#include <cstdint>
#include <string>

#include "app/die_diagnostics.hpp"
#include "fluid/fluid_state.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::app {

struct RunCounters {
  long fluid_steps = 0, pressure_iterations = 0, unconverged = 0;
  double max_divergence = 0;        // max |continuity residual| over cells with fluid [1/s]
  double max_divergence_walls = 0;  // the same over cells entirely inside walls (not imposed)
};

// The first 8 bytes of a checkpoint written by a run over MPI ranks (mpi/run_distributed.hpp):
// parcels in id order with id-keyed histories, which restart on any number of ranks.
inline constexpr uint64_t kPortableCheckpointMagic = 0x70706b636d656467ULL;  // "gdemckpp"
// True when the file starts with kPortableCheckpointMagic (false if it cannot be read).
bool is_portable_checkpoint(const std::string& path);

void write_checkpoint(const std::string& path, const std::string& config, const DemSolver& dem,
                      const fluid::FluidState* air, const DieDiagnostics& diag, const RunCounters& counters);
// Returns the configuration stored with the checkpoint. Throws cgdem::Error when the file
// is not a checkpoint of a matching case (particle count, air grid, with/without air).
std::string read_checkpoint(const std::string& path, DemSolver& dem, fluid::FluidState* air, DieDiagnostics& diag,
                            RunCounters& counters);

// 64-bit FNV-1a digest of the physical state (DEM archive and air fields), printed at the
// end of a run so that two runs can be compared bit for bit.
// The air state (t and the fields u, v, w, p, eps, eps_old with their ghost layers) as a
// checkpoint holds it; get_air throws cgdem::Error for fields of another grid size.
void put_air(io::ArchiveWriter& w, const fluid::FluidState& air);
void get_air(io::ArchiveReader& r, fluid::FluidState& air);

uint64_t state_digest(const DemSolver& dem, const fluid::FluidState* air);

}  // namespace cgdem::app
