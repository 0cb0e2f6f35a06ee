// The nonlinear solve of the implicit drag coupling (CoupledParams::coupling = Implicit).
//
// In the semi-implicit step the drag coefficient c_p = V_p beta/(1-eps) is frozen at the
// start of the step: the slip |u_f - v_p| and eps at t^n. The implicit step asks instead
// for the air velocity u^{n+1} whose own drag, evaluated at the NEW relative velocity
// |u^{n+1}(x_p) - vbar_p| and eps^{n+1}, produces it:
//
//   u = G(u),  G(u) = the air step (predictor, IBM forcing, pressure projection) with the
//                     drag sources K(u), Kv(u) deposited from c_p(u)
//
// G is linear in everything but the coefficient, so the pressure and the IBM forcing are
// solved together with the drag: every evaluation of G is one complete air step from the
// same state u^n (the existing multigrid / CHOLMOD pressure solve inside it). The unknown is
// the vector of all face velocities (the three MAC components, boundary faces included,
// which G leaves at their prescribed values). KINSOL solves it, with SUNDIALS' serial
// N_Vector doing the vector work:
//
//   anderson  KINSOL's fixed-point iteration with Anderson acceleration of depth m
//             (KIN_FP, KINSetMAA); each iteration costs one air step
//   newton    KINSOL's inexact Newton method on F(u) = u - G(u) with line search, Krylov
//             solver SPGMR, J v by KINSOL's difference quotient (one air step per product);
//             no preconditioner: F' = I - G' and G' is small (the drag's dependence on the
//             slip is weak relative to its value), so I itself is the natural one
//
// Convergence: max over the faces of |G(u) - u| <= tol [m/s], measured by this class at the
// last evaluation of G (the state the caller keeps is that evaluation's). Not converged in
// max_iterations, or KINSOL failing, is reported in the stats (converged = false); the
// coupled solver then stops the run with the time and the residual (no silent fallback).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cgdem {

struct ImplicitDragOptions {
  std::string method = "anderson";  // "anderson" | "newton"
  double tol = 1e-5;                // [m/s] max |G(u) - u| over the faces
  int max_iterations = 30;          // nonlinear iterations (KINSetNumMaxIters)
  int depth = 1;                    // Anderson depth m (method "anderson")

  void validate() const;
  static std::vector<std::string> methods() { return {"anderson", "newton"}; }
};

struct ImplicitDragStats {
  int iterations = 0;          // KINSOL's nonlinear iterations
  int evaluations = 0;         // evaluations of G (air steps), difference quotients included
  long linear_iterations = 0;  // SPGMR iterations (method "newton")
  double residual = 0;         // max |G(u) - u| at the last evaluation [m/s]
  double first_residual = 0;   // the same at the first evaluation (u = u^n)
  std::vector<double> history; // the residual of every evaluation, in order
  bool converged = false;
  int kinsol_flag = 0;         // KINSol's return value
};

class ImplicitDragSolver {
 public:
  // n: length of the unknown vector.
  ImplicitDragSolver(long n, ImplicitDragOptions opt);
  ~ImplicitDragSolver();
  ImplicitDragSolver(const ImplicitDragSolver&) = delete;
  ImplicitDragSolver& operator=(const ImplicitDragSolver&) = delete;

  // G(in, out): writes G(in) into out (both of length n).
  using Map = std::function<void(const double* in, double* out)>;
  // u: the initial guess on entry; on exit the input of the last evaluation of G (whose
  // output the caller's state holds), i.e. the accepted iterate.
  ImplicitDragStats solve(const Map& G, std::vector<double>& u);

  const ImplicitDragOptions& options() const { return opt_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  ImplicitDragOptions opt_;
};

}  // namespace cgdem
