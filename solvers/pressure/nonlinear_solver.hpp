// Nonlinear pressure equation with a solution-dependent face coefficient (KINSOL).
//
//     div( a(grad phi) grad phi ) = rhs,   discretely  F(phi) = A(a(g(phi))) phi + rhs = 0,
//
// where g(phi) are the face-normal gradients (MAC layout of pressure_solver.hpp):
//   interior / periodic-wrap face  g = (phi_hi - phi_lo) / h
//   Open boundary face             g = +2 phi_c/h (low side), -2 phi_c/h (high side): phi = 0 on the face
//   Wall boundary face             g = 0
// and coef_fn maps g -> a (e.g. a = eps^2/(eps rho_f/dt + beta(|u-v|)) with Ergun's inertial
// term, eq. (9) of the paper, making beta and hence a depend on the relative velocity).
// Method: KINSOL inexact Newton with line search; J v by KINSOL's difference quotient; Krylov
// solver SPFGMR (flexible, because the preconditioner is itself iterative), right-preconditioned
// by the linear pressure solve with the coefficient frozen at the current iterate (Picard
// linearisation): psetup sets a(g(phi_k)), psolve solves A(a_k) z = v to inner_rel_tol.
// KINSetMaxNewtonStep is set large: KINSOL's default (1000 ||u0||) is 0 from phi = 0.
// Converged when ||F||_inf <= ftol ||rhs||_inf.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::pressure {

struct FaceFields {
  std::vector<double> x, y, z;  // MAC layout: (nx+1)ny nz, nx(ny+1)nz, nx ny(nz+1)
};
// Reads the face-normal gradients, writes the face coefficients (sizes preset by the caller).
using CoefFn = std::function<void(const FaceFields& grad, FaceFields& a)>;

struct NonlinearStats {
  int newton_iterations = 0;
  long linear_iterations = 0;  // outer SPFGMR iterations
  double rel_fnorm = 0;        // ||F||_inf / ||rhs||_inf at exit
  double seconds = 0;
  bool converged = false;
};

class NonlinearPressureSolver {
 public:
  // inner.method is the linear solver used as preconditioner (e.g. "pcg-mg").
  NonlinearPressureSolver(const GridSpec& g, const SolverOptions& inner, double ftol = 1e-8,
                          int max_newton = 50, double inner_rel_tol = 1e-3);
  ~NonlinearPressureSolver();
  // phi: initial guess on entry (zero is fine), solution on exit.
  NonlinearStats solve_nonlinear(const CoefFn& coef_fn, const std::vector<double>& rhs, std::vector<double>& phi);

  // g(phi) on all faces (exposed for tests and for the fluid stepper's drag update).
  static void face_gradients(const GridSpec& g, const double* phi, FaceFields& grad);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cgdem::pressure
