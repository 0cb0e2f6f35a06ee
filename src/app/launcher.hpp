// Guard against starting the single-process `cgdem` as several processes of an MPI
// launcher (`mpirun -np N cgdem run CASE.toml`). Without it, each of the N copies would
// run the whole case and write the same output folder at once: N times the work and
// interleaved, possibly corrupt files. The binary does not call MPI, so it recognises the
// launcher by the variables that launchers export to every process.
#pragma once
#include <string>

namespace cgdem::app {

struct LaunchedAs {
  int size = 1;          // processes the launcher started (1: not launched, or -np 1)
  int rank = 0;          // this process's rank among them
  std::string variable;  // the variable that gave the size, e.g. "OMPI_COMM_WORLD_SIZE"
};

// Reads OMPI_COMM_WORLD_SIZE/_RANK (OpenMPI), PMI_SIZE/PMI_RANK (MPICH, Intel MPI) and
// SLURM_NTASKS/SLURM_PROCID (srun). The first one that is set wins.
LaunchedAs launched_as();

// Throws cgdem::Error naming the launcher variable when size > 1, for `command` (e.g.
// "run"); the message says what to do instead.
void require_single_process(const LaunchedAs& l, const std::string& command);

}  // namespace cgdem::app
