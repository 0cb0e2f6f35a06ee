// The pressure problem of the die-filling grid that the pressure benchmarks solve
// (`cgdem bench pressure`, bench/pressure/pressure_bench.cpp, and the distributed
// bench_pressure_mpi, bench/mpi_air/pressure_mpi.cpp), the domain 84 x 42 x 30 mm cut into
// nx x ny x nz cells (the paper's grid: 140 x 70 x 50, dx = 0.6 mm).
//
// Face coefficient of the pressure equation from the semi-implicit momentum update
//   eps rho_f (u* - u^n)/dt = -eps grad p - beta (u* - v)
//   =>  u* = (eps rho_f/dt u^n + beta v - eps grad p) / (eps rho_f/dt + beta),
// so div(eps u*) = 0 gives div(a grad p) = rhs with a = eps^2 / (eps rho_f/dt + beta).
// beta from Ergun (docs/model.md, Drag: eq. (9) of the paper, Ergun branch):
//   beta = 150 mu (1-eps)^2 / (eps d^2) + 1.75 (1-eps) rho_f |u-v| / d,
// d = 125 um, mu = 1.8e-5 Pa s, rho_f = 1 kg/m^3, dt = 1e-4 s, |u-v| = 0.05 m/s.
// Packed (eps = 0.45): the die x in [37,47], y in [6,36], z in [2,14] mm and the shoe cavity
// x in [22,32], y in [6,36], z in [14,24] mm; free air elsewhere (eps = 1, beta = 0).
// Solids (a = 0 on every face touching them): the table z < 14 mm outside the die, and the shoe
// walls, 3 mm thick around the cavity. Domain: Open at +z, Wall elsewhere. Face a = harmonic
// mean of the two cells. rhs: deterministic noise in [-1,1] (all wavelengths) in air cells.
#pragma once
#include <vector>

#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::bench {

struct DieFillProblem {
  pressure::GridSpec g;
  std::vector<double> ax, ay, az, rhs;  // face coefficients and right-hand side (pressure_solver.hpp layout)
};

DieFillProblem die_fill_problem(int nx, int ny, int nz);

}  // namespace cgdem::bench
