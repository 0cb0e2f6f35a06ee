// `mpirun -np N cgdem run CASE.toml`: a particle case in vacuum over N MPI ranks (issue 6).
//
// Every rank builds the case as a single process would (same insertion from the same seed)
// and keeps the parcels of its block of the DEM domain (parallel::Decomposition, dims by
// choose_dims); parallel::DistributedDem steps them with ghost parcels. Outputs are those
// of the single-process run, written by rank 0 from gathered data: energy.csv from the
// totals over the ranks, snapshots and last_good.h5 from the gathered parcels (in id order,
// as a single process writes them), diagnostics.csv and impacts.csv from the gathered
// parcels, metrics.csv, config.resolved.toml. checkpoint.bin (and settled.bin) are
// portable: parcels in id order with id-keyed histories (parallel/portable_state.hpp), so
// that a run restarts from them on any number of ranks, 1 included (under mpirun).
//
// Results agree with the single-process run to round-off that the granular flow
// amplifies, not bit for bit: a parcel's contact forces are summed in its rank's order.
// Air is not distributed yet (its halo exchange and pressure solve exist as tested pieces,
// docs/scale_out.md): a case with [air] stops with a message.
#pragma once
#include <mpi.h>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/run_case.hpp"
#include "app/run_command.hpp"

namespace cgdem::app {

// `cgdem run` over MPI_COMM_WORLD: MPI_Init, run_case_file(r) with r.distributed, and
// MPI_Finalize. Errors: the same bad input on every rank (ConfigError) is printed once,
// by rank 0; an error raised on every rank together (parallel::RaisedTogether: the run's
// own checks and outputs, and the exchanges inside the DEM step) is printed by the ranks
// that found it and ends every rank cleanly; any other error is printed by its rank, which
// then aborts the job (MPI_Abort), so that no rank waits for it forever. Returns the exit status.
int run_distributed_main(int& argc, char**& argv, RunRequest r);

// Collective over comm. Returns the exit status; errors are raised on every rank together.
int run_case_distributed(MPI_Comm comm, const DemCase& c, const AirCase& air, const DiagnosticsSpec& diag,
                         const RunInfo& info);

}  // namespace cgdem::app
