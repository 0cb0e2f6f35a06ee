#include "solvers/coupled/coupled_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace cgdem {

CoupledSolver::CoupledSolver(DemSolver& dem, fluid::FluidSolver& fluid, fluid::FluidState& air,
                             coupling::Exchange exchange, CoupledParams params)
    : dem_(dem), fluid_(fluid), air_(air), ex_(std::move(exchange)), params_(params) {
  if (!(params_.dt_fluid_max > 0)) throw Error("coupled solver: dt_fluid_max must be > 0");
  dem_.enable_air_forces(true);
  air_.t = dem_.time();
  t_weights_ = timers_.id("kernel weights");
  t_gather_ = timers_.id("air -> parcels");
  t_map_ = timers_.id("void fraction");
  t_deposit_ = timers_.id("parcels -> air");
  t_walls_ = timers_.id("IBM fractions");
  // Not kept as the first step's weights: a restart replaces the parcels after this.
  walls_at(air_.t);
  {
    coupling::ParcelWeights w;
    ex_.weights(dem_.particles(), dem_.owned(), w);
    void_stats_ = ex_.void_fraction(dem_.particles(), w, air_.eps, por_);
  }
  air_.eps_old = air_.eps;
  ex_.set_void_fields(&por_);
  if (params_.coupling == DragCoupling::Implicit) {
    for (int side = 0; side < 6; ++side)  // the air solver's sync is set before this solver is made
      if (fluid_.sync().is_cut(side))
        throw Error("coupled solver: the implicit drag coupling runs on one process only (air.coupling = "
                    "\"implicit\" over several MPI ranks is not implemented)");
    const auto& g = air_.grid;
    long n = 0;
    for (int d = 0; d < 3; ++d) {
      const auto e = g.face_extent(d);
      n += static_cast<long>(e[0]) * e[1] * e[2];
    }
    implicit_ = std::make_unique<ImplicitDragSolver>(n, params_.implicit);
    u_vec_.assign(n, 0.0);
  }
}

namespace {

// The interior face values of u, v, w one after the other (boundary faces included).
void pack_faces(const fluid::FluidState& s, double* out) {
  long q = 0;
  for (int d = 0; d < 3; ++d) {
    const fluid::Field& f = s.vel(d);
    for (int k = 0; k < f.nk(); ++k)
      for (int j = 0; j < f.nj(); ++j) {
        const double* r = f.data() + f.index(0, j, k);
        std::copy(r, r + f.ni(), out + q);
        q += f.ni();
      }
  }
}

void unpack_faces(const double* in, fluid::FluidState& s) {
  long q = 0;
  for (int d = 0; d < 3; ++d) {
    fluid::Field& f = s.vel(d);
    for (int k = 0; k < f.nk(); ++k)
      for (int j = 0; j < f.nj(); ++j) {
        std::copy(in + q, in + q + f.ni(), f.data() + f.index(0, j, k));
        q += f.ni();
      }
  }
}

}  // namespace

void CoupledSolver::implicit_air_step(double t_end, CoupledStepStats& st) {
  Particles& p = dem_.particles();
  const double dt = st.dt_fluid;
  const auto frame = dem_.scene().at(t_end);
  ex_.mean_parcel_velocities(p, w_.size(), dt, vbar_);
  air_n_ = air_;            // u^n, p^n (the guess of the first solve), eps^n, eps^{n+1}
  fluid::FluidState trial = air_;  // holds the iterate u^{n+1,k} and eps^{n+1} for the coefficient
  int pressure_iterations = 0;
  // G(u): the air step from t^n with the drag coefficient at u. Its pressure starts from
  // the previous evaluation's (a warm start: the result does not depend on it beyond the
  // pressure tolerance).
  auto G = [&](const double* in, double* out) {
    unpack_faces(in, trial);
    { auto t = timers_.scope(t_deposit_);
      ex_.drag_at(trial, w_, p, vbar_, c_);
      ex_.deposit_drag(w_, c_, vbar_, src_); }
    air_.u = air_n_.u, air_.v = air_n_.v, air_.w = air_n_.w;  // the state of t^n but its pressure
    air_.eps = air_n_.eps, air_.eps_old = air_n_.eps_old, air_.t = air_n_.t;
    st.fluid = fluid_.advance(air_, frame, src_, dt);
    pressure_iterations += st.fluid.pressure_iterations;
    pack_faces(air_, out);
  };
  pack_faces(air_n_, u_vec_.data());
  st.drag = implicit_->solve(G, u_vec_);
  st.fluid.pressure_iterations = pressure_iterations;
  if (!st.drag.converged)
    throw Error(fmt::format("coupled step t = {:.6g} -> {:.6g} s: the implicit drag coupling ({}) did not converge: "
                            "max |G(u) - u| = {:.3e} m/s > tolerance {:.3e} m/s after {} iterations ({} air steps, "
                            "KINSOL flag {}); raise air.implicit.max_iterations, loosen air.implicit.tolerance or "
                            "shorten air.dt_max",
                            air_n_.t, t_end, implicit_->options().method, st.drag.residual, implicit_->options().tol,
                            st.drag.iterations, st.drag.evaluations, st.drag.kinsol_flag));
  // air_ holds the evaluation at u_vec_ (the accepted iterate) and c_ its coefficients.
}

void CoupledSolver::walls_at(double t) {
  // The air solver's fractions (cached by body position: only the band around the moving
  // parts is re-evaluated, and its step at t then finds them current).
  frame_ = dem_.scene().at(t);
  fluid_.update_walls(frame_);
  ex_.set_walls(&fluid_.ibm());
  ex_.set_frame(&frame_);
}

// The parcels' kernel weights at their current positions with the walls at t. They stay
// valid until the next DEM substep: the next step's gather at t^n reuses those of this
// step's end (same positions, same walls); a restart or the first step builds them.
void CoupledSolver::weights_at(double t) {
  {  // timed here, not in walls_at: the constructor's first (whole-grid) evaluation comes
     // before a run's clock starts
    auto s = timers_.scope(t_walls_);
    walls_at(t);
  }
  auto s = timers_.scope(t_weights_);
  ex_.weights(dem_.particles(), dem_.owned(), w_);  // not the ghosts of other ranks' parcels
  weights_fresh_ = true;
}

int CoupledSolver::substeps() const {
  const double dt = std::min(params_.dt_fluid_max, fluid_.stable_dt(air_));
  return std::max(1, static_cast<int>(std::floor(dt / dem_.params().dt * (1 + 1e-12))));
}

void CoupledSolver::advance_particles(int n_sub) {
  Particles& p = dem_.particles();
  const double dt_f = n_sub * dem_.params().dt;
  if (!params_.move_particles) {  // held in place: the drag impulse of a fixed velocity
    for (size_t i = 0; i < p.size(); ++i) p.j_drag[i] = (dt_f * p.drag[i]) * (p.u_fluid[i] - p.v[i]);
    dem_.set_time(dem_.time() + dt_f);
    return;
  }
  weights_fresh_ = false;  // the parcels move (and may be re-sorted)
  std::fill(p.j_drag.begin(), p.j_drag.end(), Vec3{});
  dem_.advance(n_sub);  // the kicks add to j_drag (which moves with re-sorts)
}

CoupledStepStats CoupledSolver::step() {
  CoupledStepStats st;
  st.substeps = substeps();
  st.dt_fluid = st.substeps * dem_.params().dt;
  const double t_end = air_.t + st.dt_fluid;
  Particles& p = dem_.particles();

  if (!weights_fresh_) {                                              // kernel weights at x^n, alpha at t^n
    weights_at(air_.t);
    if (ex_.params().wall_porosity == coupling::WallPorosity::Packing) {  // the mixture at t^n (a start
      fluid::Field eps_n = air_.eps;                                        // or a restart)
      auto t = timers_.scope(t_map_);
      ex_.void_fraction(p, w_, eps_n, por_);
    }
  }
  { auto t = timers_.scope(t_gather_);
    ex_.air_to_parcels(air_, w_, p); }                                 // 1. u_f, c_p, f_ext at t^n
  advance_particles(st.substeps);                                     // 2. DEM substeps
  weights_at(t_end);                                                  //    x^{n+1}, alpha at t^{n+1}
  { auto t = timers_.scope(t_map_);
    std::swap(mix_old_, por_.mix);
    void_stats_ = ex_.void_fraction(p, w_, air_.eps, por_);           // 3. eps^{n+1}
    for (int q = 0; q < 2; ++q) capacity_nodes_[q] += void_stats_.capacity_nodes[q];
    ex_.porosity_source(por_, mix_old_, air_.eps, air_.eps_old, st.dt_fluid, src_.mass); }
  if (implicit_ && params_.feedback) {
    implicit_air_step(t_end, st);                                     // 4'-5'. air, drag at u^{n+1}
    if (params_.move_particles) {
      auto t = timers_.scope(t_gather_);
      ex_.correct_parcels_implicit(air_, w_, st.dt_fluid, c_, vbar_, p); }  // 6'.
  } else {
    { auto t = timers_.scope(t_deposit_);
      if (params_.feedback) ex_.parcels_to_air(p, w_, st.dt_fluid, src_);  // 4. K, Kv (eq. 14)
      else src_.K = src_.Kv = {}; }
    st.fluid = fluid_.advance(air_, dem_.scene().at(t_end), src_, st.dt_fluid);  // 5. air
    if (params_.move_particles) {
      auto t = timers_.scope(t_gather_);
      ex_.correct_parcels(air_, w_, st.dt_fluid, p); }                 // 6. end-of-step forces
  }
  air_.t = t_end;
  dem_.set_time(t_end);  // removes the round-off of N additions of dt_DEM
  st.void_fraction = void_stats_;
  return st;
}

}  // namespace cgdem
