// hypre's structured multigrid PFMG as the preconditioner "pfmg" of dist_pressure.hpp.
//
// The operator of dist_poisson.hpp is handed to hypre as a 7-point Struct matrix on the global
// index space, each rank giving the box of its block (the cut couplings are the same weights
// on both sides). One PFMG V-cycle per application, zero initial guess, Galerkin coarse
// operators (RAP type 0), one weighted-Jacobi sweep before and one after the coarse
// correction (relax type 1): a linear, symmetric preconditioner, as PCG needs.
// Why Jacobi: with hypre's red-black Gauss-Seidel (relax type 2) PCG stalled on the singular
// all-Wall test problem (relative residual stuck near 1e-8 after 2000 iterations), and on the
// die-filling grid it took the same 17 iterations as Jacobi, for no gain in time.
// A cell with all faces blocked (zero row) gets diagonal 1; the solver zeroes it anyway.
//
// Built when CMake finds hypre (libhypre-dev, CGDEM_HAVE_HYPRE); otherwise asking for it
// throws cgdem::Error.
#pragma once
#include <memory>

#include "solvers/pressure_mpi/dist_pressure.hpp"

namespace cgdem::air_mpi {

std::unique_ptr<DistPreconditioner> make_pfmg_preconditioner(const DistPoisson& op);
bool have_pfmg();

}  // namespace cgdem::air_mpi
