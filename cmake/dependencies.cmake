# Every dependency is a Debian 12 package (see README.md, scripts/install-deps.sh).
find_package(OpenMP REQUIRED COMPONENTS C CXX)
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(fmt REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(SUNDIALS REQUIRED)
find_package(GTest)
# Optional: the single-process build needs no MPI (CGDEM_MPI in CMakeLists.txt).
find_package(MPI COMPONENTS CXX)

# toml11 and CLI11 are header-only; Debian installs them in /usr/include.
find_path(TOML11_INCLUDE_DIR toml.hpp REQUIRED)
find_path(CLI11_INCLUDE_DIR CLI/CLI.hpp REQUIRED)

# FFTW and SuiteSparse 5.12 ship no CMake config: pkg-config / find_library.
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
find_library(FFTW3_OMP_LIB fftw3_omp REQUIRED)
# hdf5-serial explicitly: with OpenMPI installed the plain "hdf5" module is the MPI one.
pkg_check_modules(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial)
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIB cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIB suitesparseconfig REQUIRED)
add_library(cgdem_suitesparse INTERFACE)
target_include_directories(cgdem_suitesparse INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(cgdem_suitesparse INTERFACE ${CHOLMOD_LIB} ${SUITESPARSECONFIG_LIB})
# Optional, with MPI only: hypre's structured multigrid (libhypre-dev, headers in
# /usr/include/hypre, no CMake config) for the "pfmg" preconditioner of solvers/pressure_mpi.
if(MPI_CXX_FOUND)
  find_path(HYPRE_INCLUDE_DIR HYPRE_struct_ls.h PATH_SUFFIXES hypre)
  find_library(HYPRE_LIB HYPRE)
endif()
