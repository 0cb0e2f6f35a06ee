// Interface of the pressure (projection) solvers: the variable-coefficient Poisson problem
//
//     div( a grad phi ) = rhs        on a uniform nx x ny x nz cell-centred grid,
//
// discretised with the standard 7-point stencil: for cell c and each face f towards a
// neighbour nb,   sum_f  a_f (phi_nb - phi_c) / h_f^2  = rhs_c.
// Face coefficients a_f >= 0 live on the faces of a MAC grid:
//   ax: (nx+1) * ny * nz, face i sits between cells i-1 and i, index i + (nx+1)*(j + ny*k)
//   ay: nx * (ny+1) * nz,  index i + nx*(j + (ny+1)*k)
//   az: nx * ny * (nz+1),  index i + nx*(j + ny*k)
// Cells: index i + nx*(j + ny*k). Domain faces per side (-x,+x,-y,+y,-z,+z):
//   Wall      zero flux (the domain face coefficient is ignored),
//   Open      phi = 0 on the face (ghost value -phi_c, using the face coefficient),
//   Periodic  both sides of the axis must be Periodic (face coefficient at i=0 is used
//             for the wrap-around face; the face at i=nx is ignored).
// A face with a = 0 (e.g. inside a solid) carries no flux. When no side is Open the
// problem is singular: the solvers remove the mean of rhs and return mean-free phi.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "fluid/pressure_options.hpp"

namespace cgdem::pressure {

enum class Boundary { Wall, Open, Periodic };

struct GridSpec {
  int nx = 0, ny = 0, nz = 0;
  double dx = 1, dy = 1, dz = 1;
  std::array<Boundary, 6> bc{Boundary::Wall, Boundary::Wall, Boundary::Wall,
                             Boundary::Wall, Boundary::Wall, Boundary::Wall};
  long cells() const { return static_cast<long>(nx) * ny * nz; }
};

// SolverOptions (method, Krylov engine, tolerance, iteration limit): fluid/pressure_options.hpp.

struct SolveStats {
  int iterations = 0;
  double rel_residual = 0;
  double seconds = 0;
  bool converged = false;
};

class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  // New coefficients (every step in a coupled run); expensive set-up happens here.
  virtual void set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                                const std::vector<double>& az) = 0;
  // phi holds the initial guess on entry and the solution on exit.
  virtual SolveStats solve(const std::vector<double>& rhs, std::vector<double>& phi) = 0;
  // Changes SolverOptions::rel_tol for the following solves (> 0).
  virtual void set_rel_tol(double rel_tol) = 0;
};

// The registered methods (SolverOptions::method), with one line of documentation each, in
// the registry's order; their names alone.
struct PressureMethodInfo {
  const char* name;
  const char* doc;
};
std::vector<PressureMethodInfo> pressure_methods();
std::vector<std::string> pressure_method_names();

// The solver of opt.method; throws cgdem::Error naming the allowed methods for any other
// name, and for an inconsistent grid.
std::unique_ptr<PressureSolver> make_pressure_solver(const GridSpec& grid, const SolverOptions& opt);

}  // namespace cgdem::pressure
