# One library per module so that each can be built and tested on its own.
# Sources are globbed per folder (CONFIGURE_DEPENDS): adding a file needs no CMake edit.
function(cgdem_module name)
  cmake_parse_arguments(M "" "" "DIRS;DEPS" ${ARGN})
  set(srcs "")
  foreach(d ${M_DIRS})
    file(GLOB s CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${d}/*.cpp)
    list(APPEND srcs ${s})
  endforeach()
  if(NOT srcs)  # a module not written yet still gives a (empty) library
    set(srcs ${PROJECT_BINARY_DIR}/generated/${name}_empty.cpp)
    file(WRITE ${srcs} "// empty module\n")
  endif()
  add_library(${name} STATIC ${srcs})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${M_DEPS})
  target_compile_options(${name} PRIVATE -Wall -Wextra)
endfunction()

# Git revision baked into the binary (refreshed at every build).
add_custom_target(cgdem_revision
  COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DVERSION=${PROJECT_VERSION} -DOUT=${PROJECT_BINARY_DIR}/generated/cgdem_revision.hpp
          -P ${PROJECT_SOURCE_DIR}/cmake/revision.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/generated/cgdem_revision.hpp)

cgdem_module(cgdem_core DIRS src/core DEPS fmt::fmt OpenMP::OpenMP_CXX)
target_include_directories(cgdem_core PUBLIC ${TOML11_INCLUDE_DIR} ${CLI11_INCLUDE_DIR} ${PROJECT_BINARY_DIR}/generated)
add_dependencies(cgdem_core cgdem_revision)
cgdem_module(cgdem_geometry DIRS src/geometry DEPS cgdem_core)
cgdem_module(cgdem_io DIRS src/io DEPS cgdem_core PkgConfig::HDF5)
cgdem_module(cgdem_dem DIRS src/particles src/contact solvers/dem DEPS cgdem_geometry cgdem_io)
cgdem_module(cgdem_pressure DIRS solvers/pressure
  DEPS cgdem_core SUNDIALS::kinsol SUNDIALS::nvecserial PkgConfig::FFTW3 ${FFTW3_OMP_LIB} cgdem_suitesparse)
cgdem_module(cgdem_fluid DIRS src/fluid solvers/fluid DEPS cgdem_pressure cgdem_geometry cgdem_io)
cgdem_module(cgdem_coupling DIRS src/coupling solvers/coupled DEPS cgdem_dem cgdem_fluid)
# The observables of a run read from the parcels and the air (the die-filling diagnostics).
cgdem_module(cgdem_diagnostics DIRS src/diagnostics DEPS cgdem_dem cgdem_fluid)
# The building blocks of the decomposition: blocks of parcels and of air cells, parcel
# migration with contact history, the portable state; with MPI, src/parallel/mpi: the
# exchanges, gathers and halos over ranks.
if(CGDEM_MPI)
  cgdem_module(cgdem_parallel DIRS src/parallel src/parallel/mpi DEPS cgdem_dem cgdem_fluid MPI::MPI_CXX)
else()
  cgdem_module(cgdem_parallel DIRS src/parallel DEPS cgdem_dem cgdem_fluid)
endif()
# The time steppers over MPI ranks: the distributed DEM step (solvers/dem_mpi) and the
# distributed pressure solve (solvers/pressure_mpi: SUNDIALS' MPI NVECTOR, optional hypre).
if(CGDEM_MPI)
  cgdem_module(cgdem_distributed DIRS solvers/dem_mpi solvers/pressure_mpi
    DEPS cgdem_parallel cgdem_pressure SUNDIALS::nvecparallel MPI::MPI_CXX)
  if(HYPRE_INCLUDE_DIR AND HYPRE_LIB)
    target_include_directories(cgdem_distributed PUBLIC ${HYPRE_INCLUDE_DIR})
    target_link_libraries(cgdem_distributed PUBLIC ${HYPRE_LIB})
    target_compile_definitions(cgdem_distributed PRIVATE CGDEM_HAVE_HYPRE)
  else()
    message(STATUS "cgdem: hypre not found: the distributed pressure solve has no 'pfmg' preconditioner")
  endif()
endif()
# The run driver (solvers/run): the sequence of a run, its communicator (the identity on
# one process), what advances a case with parcels, and its checkpoints; over MPI ranks
# (solvers/run_mpi) the communicator and the decomposition into blocks.
cgdem_module(cgdem_run DIRS solvers/run DEPS cgdem_coupling cgdem_parallel)
if(CGDEM_MPI)
  cgdem_module(cgdem_run_mpi DIRS solvers/run_mpi DEPS cgdem_run cgdem_distributed)
endif()

# The command line: its case readers, the phases of its runs and their outputs and
# diagnostics are a library (tested in tests/app); the executable is main.cpp.
file(GLOB CGDEM_APP_SRCS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/app/*.cpp)
list(REMOVE_ITEM CGDEM_APP_SRCS ${PROJECT_SOURCE_DIR}/src/app/main.cpp)
add_library(cgdem_app STATIC ${CGDEM_APP_SRCS})
target_link_libraries(cgdem_app PUBLIC cgdem_dem cgdem_fluid cgdem_coupling cgdem_diagnostics cgdem_run)
target_compile_options(cgdem_app PRIVATE -Wall -Wextra)
# `mpirun -np N cgdem run` (src/app/mpi): only in builds with MPI; a single-process run
# never initialises MPI.
if(CGDEM_MPI)
  target_sources(cgdem_app PRIVATE ${PROJECT_SOURCE_DIR}/src/app/mpi/run_distributed.cpp)
  target_link_libraries(cgdem_app PUBLIC cgdem_run_mpi)
  target_compile_definitions(cgdem_app PUBLIC CGDEM_WITH_MPI)
endif()
# The analysis on top of runs (coarse-grain scaling, spectra, convergence studies).
cgdem_module(cgdem_scaling DIRS scaling DEPS cgdem_app PkgConfig::FFTW3 Eigen3::Eigen)
add_executable(cgdem ${PROJECT_SOURCE_DIR}/src/app/main.cpp)
target_link_libraries(cgdem PRIVATE cgdem_app cgdem_scaling)
target_compile_options(cgdem PRIVATE -Wall -Wextra)

if(CGDEM_BUILD_TESTS AND GTest_FOUND)
  enable_testing()
  include(GoogleTest)
  # One test executable per module: tests/<module>/*.cpp
  function(cgdem_tests module lib)
    file(GLOB s CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/${module}/*.cpp)
    if(s)
      add_executable(test_${module} ${s})
      target_link_libraries(test_${module} PRIVATE ${lib} GTest::gtest_main)
      target_compile_definitions(test_${module} PRIVATE CGDEM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                 CGDEM_BINARY_DIR="${PROJECT_BINARY_DIR}")
      gtest_discover_tests(test_${module} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${module})
    endif()
  endfunction()
  cgdem_tests(core cgdem_core)
  cgdem_tests(geometry cgdem_geometry)
  cgdem_tests(io cgdem_io)
  cgdem_tests(dem cgdem_dem)
  cgdem_tests(pressure cgdem_pressure)
  cgdem_tests(fluid cgdem_fluid)
  cgdem_tests(coupling cgdem_coupling)
  cgdem_tests(diagnostics cgdem_diagnostics)
  cgdem_tests(app cgdem_app)
  cgdem_tests(scaling cgdem_scaling)
  cgdem_tests(parallel cgdem_parallel)
  if(CGDEM_MPI)
    # A multi-rank test executable (its own main: MPI_Init around GoogleTest) from the .cpp
    # files of a folder, registered as ctest NAME_np<N> for each rank count, run under
    # mpirun oversubscribed (correctness on a 2-core machine, not speed). The launcher
    # flags are OpenMPI's (Debian's MPI, scripts/install-deps.sh); CI runs as root.
    function(cgdem_mpi_tests exe name dir)
      cmake_parse_arguments(T "" "" "LIBS;RANKS" ${ARGN})
      file(GLOB srcs CONFIGURE_DEPENDS ${dir}/*.cpp)
      add_executable(${exe} ${srcs})
      target_link_libraries(${exe} PRIVATE ${T_LIBS} GTest::gtest)
      target_compile_options(${exe} PRIVATE -Wall -Wextra)
      foreach(np ${T_RANKS})
        add_test(NAME ${name}_np${np}
                 COMMAND ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe ${MPIEXEC_NUMPROC_FLAG} ${np}
                         ${MPIEXEC_PREFLAGS} $<TARGET_FILE:${exe}> ${MPIEXEC_POSTFLAGS})
        set_tests_properties(${name}_np${np} PROPERTIES LABELS parallel TIMEOUT 120
                             ENVIRONMENT "OMP_NUM_THREADS=1;GTEST_COLOR=no")
      endforeach()
    endfunction()
    include(${PROJECT_SOURCE_DIR}/tests/parallel/mpi/mpi_tests.cmake)
    include(${PROJECT_SOURCE_DIR}/tests/parallel/mpi_air/mpi_air_tests.cmake)
  endif()
  # End-to-end checks of the command line (config errors, demo smoke run).
  if(EXISTS ${PROJECT_SOURCE_DIR}/tests/cli/cli_tests.cmake)
    include(${PROJECT_SOURCE_DIR}/tests/cli/cli_tests.cmake)
  endif()
  # One file per command's end-to-end checks (tests/cli/<command>.cli.cmake).
  file(GLOB cli_extra CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/cli/*.cli.cmake)
  foreach(f ${cli_extra})
    include(${f})
  endforeach()
endif()

# `cgdem bench ...` is part of the command line, so the benchmarks are always built.
if(EXISTS ${PROJECT_SOURCE_DIR}/bench/CMakeLists.txt)
  add_subdirectory(bench)
endif()
