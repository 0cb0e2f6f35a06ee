# Multi-rank tests of the air over ranks (src/parallel/mpi halo exchange, solvers/pressure_mpi, distributed pressure solve, the air step and
# the parcel-air exchange on blocks): one executable with its own main (MPI_Init around
# GoogleTest), run under mpirun on 1, 2 and 4 ranks, oversubscribed on a 2-core machine (for
# correctness, not speed). The 4-rank run covers the 2 x 2 x 1 and 4 x 1 x 1 cuts.
cgdem_mpi_tests(test_parallel_mpi_air parallel.mpi_air ${CMAKE_CURRENT_LIST_DIR} LIBS cgdem_distributed cgdem_coupling
                RANKS 1 2 4)
