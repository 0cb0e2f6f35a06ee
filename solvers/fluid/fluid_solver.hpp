// The air stepper: volume-averaged incompressible Navier-Stokes with immersed boundaries
// (paper eqs. 12, 13, 18-20), projection method on the MAC grid of src/fluid.
//
// One step from t^n to t^{n+1} = t^n + dt, with E = eps on the faces (mean of the two
// cells), K the implicit source coefficient, alpha/U_B the IBM fractions at t^{n+1}:
//
//   R(u, E)  = -div(E rho u u) + div(eps tau(u)) + E rho g + f_explicit        (explicit)
//   predictor (E^{n+1} rho/dt + K) u_hat = E^n rho u^n / dt + R~ + K v_p        (eq. 13)
//             R~ = R(u^n, E^n)                          (time_order 1, forward Euler)
//             R~ = [R(u^n, E^n) + R(u^(1), E^{n+1})]/2  (time_order 2, Heun; u^(1) is the
//                                                         projected stage-1 result)
//   IBM       u* = (1 - alpha) u_hat + alpha U_B,  i.e. f_IB = E rho alpha (U_B - u_hat)/dt
//                                                                            (eqs. 18-20)
//   pressure  div( a grad p ) = div(E u*) + (eps^{n+1} - eps^n)/dt,
//             a = (1 - alpha) E^2 / (E rho/dt + K)                            (eq. 12)
//   correct   u^{n+1} = u* - (a / E) grad p
//
// so that d(eps)/dt + div(E u^{n+1}) = 0 holds to the pressure solver's tolerance in every
// cell. The factor (1 - alpha) in `a` confines the pressure correction to the fluid part of
// a face control volume: a face inside a wall (alpha = 1) keeps u = U_B exactly, and the
// solid's velocity enters the divergence through u*. p is the full pressure (not an
// increment), solved each stage with the previous p as initial guess.
//
// Usage: the caller sets state.eps to eps(t^{n+1}) (state.eps_old holds eps(t^n)), passes
// the scene evaluated at t^{n+1} and the sources, and calls advance(); on return
// state.eps_old = state.eps and state.t = t^{n+1}.
#pragma once
#include <memory>

#include "core/timers.hpp"
#include "fluid/field_sync.hpp"
#include "fluid/fluid_state.hpp"
#include "fluid/ibm.hpp"
#include "fluid/momentum_terms.hpp"
#include "geometry/scene.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::fluid {

class FluidSolver {
 public:
  // Creates the pressure solver from params.pressure (make_fluid_solver.cpp).
  FluidSolver(const MacGrid& g, FluidParams params);
  // Uses the given pressure solver (built for pressure_grid(g, params)).
  FluidSolver(const MacGrid& g, FluidParams params, std::unique_ptr<pressure::PressureSolver> ps);

  // Ghost fills and grid-wide reductions go through `sync` from now on (the default:
  // SerialSync on the grid and params.bc). For a block of a grid over MPI ranks: g and
  // params.bc are the block's (air_mpi::local_boundary), the pressure solver the
  // distributed one. `sync` must outlive the solver.
  void set_sync(FieldSync& sync) { sync_ = &sync; }
  FieldSync& sync() { return *sync_; }

  StepStats advance(FluidState& s, const geometry::Scene::Frame& frame_end, const Sources& src, double dt);

  // Largest stable step: min(dt_max, cfl dx / sum_d max|u_d|, visc_safety dx^2 rho / (6 mu)),
  // the maxima over the whole grid (over every rank's block).
  double stable_dt(const FluidState& s) const;
  // max over cells of |(eps - eps_old)/dt + div(E u) + mass| for the state as it is [1/s]
  // (mass: Sources::mass of the step, empty for none): over the
  // cells with some fluid (alpha_cell < 1, where the pressure equation imposes it) and over
  // the cells entirely inside walls (alpha_cell = 1, where nothing imposes it).
  struct Divergence {
    double fluid = 0, walls = 0;
  };
  Divergence divergence(const FluidState& s, const Field& mass, double dt) const;

  const FluidParams& params() const { return params_; }
  const IbmFractions& ibm() const { return ibm_; }
  // The walls' fractions at `frame`: recomputed only when a body has moved since the last
  // call (returns whether they were), then over MPI ranks the ghosts beyond the cuts are
  // filled and any_solid is made global (a block's ghosts may reach walls it has none of).
  // advance() calls it with its end frame; a coupling that needs the fractions of that
  // frame earlier (the void fraction, the kernel masks) calls it first and reads ibm(), so
  // the fractions are computed once per step.
  bool update_walls(const geometry::Scene::Frame& frame);
  // Whether the explicit terms and the predictor pass over the faces at the ends of each row
  // that lie inside walls (on by default; the results are the same bits either way, see
  // spans_).
  void set_skip_walls(bool on) { skip_walls_ = on; }
  // Faces of component d that the explicit terms pass over (for the tests and the bench).
  long faces_in_walls(int d) const;
  const PhaseTimers& timers() const { return timers_; }
  PhaseTimers& timers() { return timers_; }

 private:
  using Faces = std::array<Field, 3>;
  void face_eps(const Field& eps_cell, Faces& E) const;
  using Vel = std::array<Field*, 3>;
  void explicit_rhs(const Vel& vel, const Field& eps_cell, const Faces& E, const Sources& src, Faces& R);
  void predict(const FluidState& s, const Faces& R0, const Faces* R1, const Sources& src, double dt, Faces& ustar);
  // Pressure p (initial guess in, solution out) and vel = ustar corrected; reads state.eps,
  // state.eps_old.
  void project(const FluidState& s, const Sources& src, double dt, Faces& ustar, const Vel& vel, Field& p,
               StepStats& st);
  void set_pressure_coefficients(const Sources& src, double dt);
  void check_inputs(const FluidState& s, const Sources& src, double dt);
  void step_statistics(const FluidState& s, const Sources& src, double dt, StepStats& st) const;
  void mark_open_spans();
  const RowSpans* spans_of(int d) const;

  MacGrid g_;
  FluidParams params_;
  std::unique_ptr<pressure::PressureSolver> ps_;
  std::unique_ptr<SerialSync> serial_sync_;
  FieldSync* sync_ = nullptr;
  IbmFractions ibm_;
  PhaseTimers timers_;
  Faces E_old_, E_new_, R0_, R1_, ustar_, u1_;  // u1_: the projected Heun stage
  Field p1_;
  std::vector<double> ax_, ay_, az_, rhs_, phi_;
  std::array<std::vector<double>, 3> next_;
  std::array<std::vector<double>, 3> corr_;  // c_f = a_f / E_f of the correction, pressure layout
  bool coeffs_set_ = false;
  // Per component d and row (j, k) of its active faces (q = (j - lo_j) + n_j (k - lo_k)): the
  // span [lo[q], hi[q]) from the first to the last face that is not wholly inside a wall.
  // A face outside it has alpha = 1 and a wall velocity U_B that is not -0, and the predictor
  // gives it (1 - 1) u_hat + 1 U_B = U_B whatever the finite u_hat (+-0 + U_B is U_B unless
  // U_B = -0). So the predictor writes U_B there and the explicit terms are evaluated on the
  // spans only. Set by update_walls whenever the fractions change.
  std::array<std::vector<int>, 3> span_lo_, span_hi_;
  std::array<std::vector<long>, 3> span_work_;  // RowSpans::work
  std::array<RowSpans, 3> spans_{};  // views of span_lo_, span_hi_, span_work_ (spans_of)
  bool skip_walls_ = true;
};

pressure::GridSpec pressure_grid(const MacGrid& g, const FluidParams& params);

}  // namespace cgdem::fluid
