# Multi-rank tests of src/parallel/mpi: one executable with its own main (MPI_Init around
# GoogleTest), run under mpirun on 4 ranks, oversubscribed on a 2-core machine (for
# correctness, not speed), on 2 (one cut) and on 1 rank (the degenerate decomposition).
# The launcher flags are OpenMPI's (Debian's MPI, scripts/install-deps.sh); CI runs as root.
file(GLOB CGDEM_MPI_TEST_SRCS CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
add_executable(test_parallel_mpi ${CGDEM_MPI_TEST_SRCS})
target_link_libraries(test_parallel_mpi PRIVATE cgdem_parallel GTest::gtest)
target_compile_options(test_parallel_mpi PRIVATE -Wall -Wextra)
foreach(np 4 2 1)
  add_test(NAME parallel.mpi_np${np}
           COMMAND ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe ${MPIEXEC_NUMPROC_FLAG} ${np}
                   ${MPIEXEC_PREFLAGS} $<TARGET_FILE:test_parallel_mpi> ${MPIEXEC_POSTFLAGS})
  set_tests_properties(parallel.mpi_np${np} PROPERTIES LABELS parallel TIMEOUT 120 ENVIRONMENT "OMP_NUM_THREADS=1;GTEST_COLOR=no")
endforeach()
# The distributed DEM benchmark is built with these tests (bench/dem_mpi).
include(${PROJECT_SOURCE_DIR}/bench/dem_mpi/bench_dem_mpi.cmake)
