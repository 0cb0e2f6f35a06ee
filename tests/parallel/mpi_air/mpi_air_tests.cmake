# Multi-rank tests of src/air_mpi (halo exchange, distributed pressure solve): one executable
# with its own main (MPI_Init around GoogleTest), run under mpirun on 1, 2 and 4 ranks,
# oversubscribed on a 2-core machine (for correctness, not speed). The 4-rank run covers the
# 2 x 2 x 1 and 4 x 1 x 1 cuts. Launcher flags are OpenMPI's (scripts/install-deps.sh).
file(GLOB CGDEM_MPI_AIR_TEST_SRCS CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
add_executable(test_parallel_mpi_air ${CGDEM_MPI_AIR_TEST_SRCS})
target_link_libraries(test_parallel_mpi_air PRIVATE cgdem_air_mpi cgdem_coupling GTest::gtest)
target_compile_options(test_parallel_mpi_air PRIVATE -Wall -Wextra)
foreach(np 1 2 4)
  add_test(NAME parallel.mpi_air_np${np}
           COMMAND ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe ${MPIEXEC_NUMPROC_FLAG} ${np}
                   ${MPIEXEC_PREFLAGS} $<TARGET_FILE:test_parallel_mpi_air> ${MPIEXEC_POSTFLAGS})
  set_tests_properties(parallel.mpi_air_np${np} PROPERTIES LABELS parallel TIMEOUT 120 ENVIRONMENT "OMP_NUM_THREADS=1;GTEST_COLOR=no")
endforeach()
