#include "solvers/dem/dem_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace cgdem {

DemSolver::DemSolver(std::vector<Species> species, const contact::ContactModel& material, const DemParams& params,
                     geometry::Scene scene)
    : species_(std::move(species)),
      tables_(contact::make_tables(species_, material)),
      params_(params),
      scene_(std::move(scene)) {
  if (params_.skin <= 0) {
    double dmax = 0;
    for (const auto& s : species_) dmax = std::max(dmax, s.diameter());
    params_.skin = 0.1 * dmax;
  }
  nl_.skin = params_.skin;
  nl_.periodic.axis = params_.periodic;
  nl_.periodic.lo = params_.domain.lo;
  nl_.periodic.hi = params_.domain.hi;
  for (int a = 0; a < 3; ++a)
    if (params_.periodic[a] && !(std::isfinite(params_.domain.lo[a]) && std::isfinite(params_.domain.hi[a]) &&
                                 params_.domain.hi[a] > params_.domain.lo[a]))
      throw ConfigError(fmt::format("periodic axis {} needs a finite domain on that axis", "xyz"[a]));
  t_kick_ = timers_.id("integrate");
  t_neigh_ = timers_.id("neighbour lists");
  t_force_ = timers_.id("contact forces");
  t_drift_ = timers_.id("integrate");
}

namespace {

// Half kick of particle i (see the header): v += h F/m (with air: the implicit drag), w += h T/I.
inline void kick_one(Particles& p, int i, double h, bool air) {
  if (air) {
    const double hm = h * p.inv_mass[i];
    const Vec3 v0 = p.v[i];
    const double c = p.drag[i];
    const Vec3 v1 = (1.0 / (1.0 + hm * c)) * (v0 + hm * (p.force[i] + c * p.u_fluid[i]));
    // Work of this kick's air impulse, exact for the kinetic energy it changes.
    const Vec3 j = (h * c) * (p.u_fluid[i] - v1);
    p.j_drag[i] += j;
    p.w_fluid[i] += dot(h * p.f_ext[i] + j, 0.5 * (v0 + v1));
    p.v[i] = v1;
  } else {
    p.v[i] += (h * p.inv_mass[i]) * p.force[i];
  }
  p.omega[i] += (h * p.inv_inertia[i]) * p.torque[i];
}

// Half kick and drift of the particles 0..n-1 (the owned ones: ghosts are refreshed from
// their owners) in one pass (one parallel region per step instead of three); returns
// max |x_i - x_at_build_i|^2 for the rebuild test (0 when there is no build yet).
double kick_and_drift(Particles& p, int n, const std::vector<Vec3>& x_at_build, double h, double dt, bool air) {
  const bool have_build = x_at_build.size() == p.size();
  double move2 = 0;
#pragma omp parallel for schedule(static) reduction(max : move2) if (n >= 512)
  for (int i = 0; i < n; ++i) {
    kick_one(p, i, h, air);
    p.x[i] += dt * p.v[i];
    if (have_build) {
      const double d2 = norm2(p.x[i] - x_at_build[i]);
      if (d2 > move2) move2 = d2;  // NaN ignored, as in NeighborList::needs_rebuild
    }
  }
  return move2;
}

}  // namespace

void DemSolver::kick(double h) {
  const int n = static_cast<int>(owned());
#pragma omp parallel for schedule(static) if (n >= 512)
  for (int i = 0; i < n; ++i) kick_one(p_, i, h, air_forces_);
}

// Owned particles only: a hook removes the ghosts before (DomainExchange::drop_ghosts).
void DemSolver::remove_escaped() {
  if (nl_.ghosts > 0) throw Error("DemSolver: escaped parcels are removed only after the ghosts were dropped");
  std::vector<int> keep;
  keep.reserve(p_.size());
  for (size_t i = 0; i < p_.size(); ++i) {
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (!params_.periodic[a]) inside = inside && p_.x[i][a] >= params_.domain.lo[a] && p_.x[i][a] <= params_.domain.hi[a];
    if (inside) {
      keep.push_back(static_cast<int>(i));
    } else {
      removed_damping_ += p_.e_damping[i];
      removed_friction_ += p_.e_friction[i];
      removed_walls_ += p_.w_walls[i];
      removed_fluid_ += p_.w_fluid[i];
      ++removed_;
    }
  }
  if (keep.size() != p_.size()) {
    p_.reorder(keep);
    // Serial: the lists are dropped, and with them every history (the behaviour the serial
    // results were made with). With a hook the histories of the others are kept: the lists
    // follow the removal, and the pairs with ghosts are records by id already.
    if (exchange_)
      nl_.retain(keep, 0);
    else
      nl_.offset.clear();
  }
}

// Rebuilds the lists at x^n (the escaped parcels removed first).
void DemSolver::rebuild_lists() {
  if (exchange_) {
    exchange_->drop_ghosts(p_, nl_);
    remove_escaped();
    exchange_->rebuild(p_, nl_, frame_);
  } else {
    remove_escaped();
    nl_.build(p_, frame_);
  }
}

void DemSolver::step() {
  const double dt = params_.dt;
  if (!forces_valid_) {  // first step (or particles were added): forces at x^n
    frame_ = scene_.at(t_);
    if (!exchange_) nl_.offset.clear();  // (a hook keeps the lists in step with its ghosts)
    {
      auto scope = timers_.scope(t_neigh_);
      rebuild_lists();
    }
    compute_forces();
    forces_valid_ = true;
  }
  double move2;
  {
    auto scope = timers_.scope(t_kick_);
    move2 = kick_and_drift(p_, static_cast<int>(owned()), nl_.x_at_build, 0.5 * dt, dt, air_forces_);
  }
  t_ += dt;
  ++steps_;
  frame_ = scene_.at(t_);
  {
    auto scope = timers_.scope(t_neigh_);
    bool rebuild = nl_.needs_rebuild(move2, p_.size(), frame_);
    if (exchange_) rebuild = exchange_->any(rebuild);
    if (rebuild)
      rebuild_lists();
    else if (exchange_)
      exchange_->refresh_ghosts(p_);
  }
  compute_forces();
  auto scope = timers_.scope(t_kick_);
  kick(0.5 * dt);
}

void DemSolver::resume(double t, long steps, long removed, const EnergyBudget& removed_accounts, Particles parcels,
                       NeighborList::Incoming histories) {
  for (int s : parcels.species)
    if (s < 0 || s >= static_cast<int>(species_.size())) throw Error("resume: unknown species index");
  p_ = std::move(parcels);
  NeighborList lists;  // none yet: the first step builds them
  lists.skin = nl_.skin;
  lists.periodic = nl_.periodic;
  lists.builds = nl_.builds;
  lists.incoming = std::move(histories);
  nl_ = std::move(lists);
  t_ = t;
  steps_ = steps;
  removed_ = removed;
  removed_damping_ = removed_accounts.dissipated_damping;
  removed_friction_ = removed_accounts.dissipated_friction;
  removed_walls_ = removed_accounts.work_walls;
  removed_fluid_ = removed_accounts.work_fluid;
  frame_ = scene_.at(t_);
  forces_valid_ = true;  // the parcels carry the forces of step `steps`
}

EnergyBudget DemSolver::removed_accounts() const {
  EnergyBudget b;
  b.dissipated_damping = removed_damping_;
  b.dissipated_friction = removed_friction_;
  b.work_walls = removed_walls_;
  b.work_fluid = removed_fluid_;
  return b;
}

long DemSolver::contact_count() const {
  long c = 0;
  const size_t n = owned();
  for (size_t i = 0; i < n; ++i) {
    for (int e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e) {
      const int j = nl_.partner[e];
      if (static_cast<size_t>(j) >= n && p_.id[j] < p_.id[i]) continue;  // counted on the ghost's rank
      const double r = p_.radius[i] + p_.radius[j];
      if (norm2(p_.x[i] - nl_.partner_x(p_, e)) < r * r) ++c;
    }
    for (int e = nl_.wall_offset[i]; e < nl_.wall_offset[i + 1]; ++e)
      if (frame_.part_distance(nl_.wall_part[e], p_.x[i]) < p_.radius[i]) ++c;
  }
  return c;
}

}  // namespace cgdem
