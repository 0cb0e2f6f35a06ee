# Multi-rank tests of src/parallel/mpi and solvers/dem_mpi: one executable with its own main (MPI_Init around
# GoogleTest), run under mpirun on 4 ranks, oversubscribed on a 2-core machine (for
# correctness, not speed), on 2 (one cut) and on 1 rank (the degenerate decomposition).
cgdem_mpi_tests(test_parallel_mpi parallel.mpi ${CMAKE_CURRENT_LIST_DIR} LIBS cgdem_distributed RANKS 4 2 1)
# The distributed DEM benchmark is built with these tests (bench/dem_mpi).
include(${PROJECT_SOURCE_DIR}/bench/dem_mpi/bench_dem_mpi.cmake)
