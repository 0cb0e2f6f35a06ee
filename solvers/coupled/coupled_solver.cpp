#include "solvers/coupled/coupled_solver.hpp"

#include <algorithm>
#include <cmath>

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
  // Not kept as the first step's weights: a restart replaces the parcels after this.
  walls_at(air_.t);
  {
    coupling::ParcelWeights w;
    ex_.weights(dem_.particles(), dem_.owned(), w);
    void_stats_ = ex_.void_fraction(dem_.particles(), w, air_.eps);
  }
  air_.eps_old = air_.eps;
}

void CoupledSolver::walls_at(double t) {
  // Cached by body position: only the band around the moving parts is re-evaluated.
  fluid::update_ibm(air_.grid, dem_.scene().at(t), fluid_.params().ibm_samples, walls_);
  // Over MPI ranks the masks read the fractions beyond the cuts (serial: nothing to do).
  fluid::FieldSync& sync = fluid_.sync();
  sync.copy_ghosts(walls_.alpha_cell, fluid::kCells);
  for (int d = 0; d < 3; ++d) sync.copy_ghosts(walls_.alpha_face[d], d);
  walls_.any_solid = sync.any(walls_.any_solid);  // a block's ghosts may reach walls it has none of
  ex_.set_walls(&walls_);
}

// The parcels' kernel weights at their current positions with the walls at t. They stay
// valid until the next DEM substep: the next step's gather at t^n reuses those of this
// step's end (same positions, same walls); a restart or the first step builds them.
void CoupledSolver::weights_at(double t) {
  walls_at(t);
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
  for (int s = 0; s < n_sub; ++s) dem_.step();  // kicks add to j_drag (which moves with re-sorts)
}

CoupledStepStats CoupledSolver::step() {
  CoupledStepStats st;
  st.substeps = substeps();
  st.dt_fluid = st.substeps * dem_.params().dt;
  const double t_end = air_.t + st.dt_fluid;
  Particles& p = dem_.particles();

  if (!weights_fresh_) weights_at(air_.t);                            // kernel weights at x^n, alpha at t^n
  { auto t = timers_.scope(t_gather_);
    ex_.air_to_parcels(air_, w_, p); }                                 // 1. u_f, c_p, f_ext at t^n
  advance_particles(st.substeps);                                     // 2. DEM substeps
  weights_at(t_end);                                                  //    x^{n+1}, alpha at t^{n+1}
  { auto t = timers_.scope(t_map_);
    void_stats_ = ex_.void_fraction(p, w_, air_.eps); }               // 3. eps^{n+1}
  { auto t = timers_.scope(t_deposit_);
    if (params_.feedback) ex_.parcels_to_air(p, w_, st.dt_fluid, src_);  // 4. K, Kv (eq. 14)
    else src_ = {}; }
  st.fluid = fluid_.advance(air_, dem_.scene().at(t_end), src_, st.dt_fluid);  // 5. air
  if (params_.move_particles) {
    auto t = timers_.scope(t_gather_);
    ex_.correct_parcels(air_, w_, st.dt_fluid, p); }                   // 6. end-of-step forces
  air_.t = t_end;
  dem_.set_time(t_end);  // removes the round-off of N additions of dt_DEM
  st.void_fraction = void_stats_;
  return st;
}

}  // namespace cgdem
