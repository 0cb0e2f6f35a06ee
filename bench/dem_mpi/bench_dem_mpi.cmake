# The distributed dense-bed DEM benchmark (issue 6): its own executable, run under mpirun;
# only with MPI. Included once (from tests/parallel/mpi/mpi_tests.cmake; it may move to
# bench/CMakeLists.txt beside bench_pressure_mpi).
if(CGDEM_MPI AND NOT TARGET bench_dem_mpi)
  add_executable(bench_dem_mpi ${CMAKE_CURRENT_LIST_DIR}/dem_mpi_bench.cpp)
  target_link_libraries(bench_dem_mpi PRIVATE cgdem_distributed)
  target_compile_options(bench_dem_mpi PRIVATE -Wall -Wextra)
endif()
