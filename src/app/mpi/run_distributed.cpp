#include "app/mpi/run_distributed.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdio>

#include "core/error.hpp"
#include "parallel/mpi/exchange.hpp"

namespace cgdem::app {

int run_distributed_main(int& argc, char**& argv, RunRequest r) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // OpenMP threads call no MPI
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  r.distributed = true;
  int status = 2;
  try {
    status = run_case_file(r);
  } catch (const parallel::RaisedTogether& e) {  // every rank is here: stop cleanly
    if (e.found_here) {
      int size = 1;
      MPI_Comm_size(MPI_COMM_WORLD, &size);
      fmt::print(stderr, "cgdem: error{}: {}\n", size > 1 ? fmt::format(" (rank {})", rank) : "", e.what());
    }
    status = 2;
  } catch (const ConfigError& e) {
    if (rank == 0) fmt::print(stderr, "cgdem: error: {}\n", e.what());
    status = 2;
  } catch (const Error& e) {
    fmt::print(stderr, "cgdem: error (rank {}): {}\n", rank, e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return status;
}

}  // namespace cgdem::app
