// `mpirun -np N cgdem run CASE.toml`: the run of particle_run.hpp over the N ranks of
// MPI_COMM_WORLD (run::MpiDomain, solvers/run_mpi/mpi_domain.hpp), with or without air.
//
// Every rank builds the case as a single process would (same insertion from the same seed)
// and keeps the parcels and air cells of its block. Outputs are those of the
// single-process run, written by rank 0 from totals and gathered data (snapshots in id
// order). Checkpoints restart on any number of ranks, one process included
// (solvers/run/run_checkpoint.hpp). Results agree with the single-process run to round-off
// that the granular flow amplifies, not bit for bit (tests/cli/mpi_run.cmake).
#pragma once
#include "app/run_command.hpp"

namespace cgdem::app {

// `cgdem run` over MPI_COMM_WORLD: MPI_Init, run_case_file(r) with r.distributed, and
// MPI_Finalize. Errors: the same bad input on every rank (ConfigError) is printed once,
// by rank 0; an error raised on every rank together (parallel::RaisedTogether: the run's
// own checks and outputs, and the exchanges inside the DEM step) is printed by the ranks
// that found it and ends every rank cleanly; any other error is printed by its rank, which
// then aborts the job (MPI_Abort), so that no rank waits for it forever. Returns the exit status.
int run_distributed_main(int& argc, char**& argv, RunRequest r);

}  // namespace cgdem::app
