#include "solvers/run/particle_stepper.hpp"

namespace cgdem::run {

ParticleStepper::ParticleStepper(Domain& domain, std::unique_ptr<DemSolver> dem, std::optional<AirSpec> air)
    : domain_(domain), dem_(std::move(dem)), air_spec_(std::move(air)) {}

ParticleStepper::~ParticleStepper() = default;

void ParticleStepper::place_parcels() {
  Particles& p = dem_->particles();
  domain_.decompose(*dem_, p.x, air_spec_ ? &*air_spec_ : nullptr);
  std::vector<int> keep;
  for (size_t i = 0; i < p.size(); ++i)
    if (domain_.owns(p.x[i])) keep.push_back(static_cast<int>(i));
  if (keep.size() != p.size()) p.reorder(keep);  // one process keeps every parcel where it is
  exchange_ = domain_.attach(*dem_);
}

void ParticleStepper::place_parcels(const parallel::PortableState& s, const RunPosition& at) {
  domain_.decompose(*dem_, s.p.x, air_spec_ ? &*air_spec_ : nullptr);
  comm().together("restart", false, [&] {
    Particles mine;
    NeighborList lists;
    parallel::restore(s, [&](const Vec3& x) { return domain_.owns(x); }, mine, lists);
    EnergyBudget removed_accounts;  // the removed parcels' totals are booked once, on rank 0
    if (comm().root()) {
      removed_accounts.dissipated_damping = at.removed_damping;
      removed_accounts.dissipated_friction = at.removed_friction;
      removed_accounts.work_walls = at.removed_walls;
      removed_accounts.work_fluid = at.removed_fluid;
    }
    dem_->resume(at.t, at.steps, comm().root() ? at.removed : 0, removed_accounts, std::move(mine),
                 std::move(lists.incoming));
  });
  exchange_ = domain_.attach(*dem_);
}

void ParticleStepper::make_air() {
  if (!air_spec_) return;
  share_ = domain_.share_air(*air_spec_);
  fluid_ = share_.pressure ? std::make_unique<fluid::FluidSolver>(share_.grid, share_.fluid, std::move(share_.pressure))
                           : std::make_unique<fluid::FluidSolver>(share_.grid, share_.fluid);
  if (share_.sync) fluid_->set_sync(*share_.sync);
  air_ = fluid::make_fluid_state(share_.grid);
  coupling::Exchange exchange(share_.grid, dem_->species(), share_.exchange);
  if (share_.sync) exchange.set_sync(share_.sync);
  coupled_ = std::make_unique<CoupledSolver>(*dem_, *fluid_, air_, std::move(exchange), air_spec_->coupled);
}

void ParticleStepper::take_air(const fluid::FluidState& whole) {
  domain_.take(whole, air_);
  fluid::FieldSync& sync = fluid_->sync();  // ghosts from the boundaries and the neighbouring blocks
  sync.fill_velocity(air_.u, air_.v, air_.w);
  sync.fill_scalar(air_.p, fluid::ScalarKind::Pressure);
  sync.fill_scalar(air_.eps, fluid::ScalarKind::ZeroGradient);
  sync.fill_scalar(air_.eps_old, fluid::ScalarKind::ZeroGradient);
}

StepDone ParticleStepper::step() {
  StepDone done;
  const long before = dem_->steps();
  if (coupled_) {
    done.coupled = coupled_->step();
    done.dt = done.coupled->dt_fluid;
  } else {
    dem_->step();
    done.dt = dem_->params().dt;
  }
  done.dem_steps = dem_->steps() - before;
  return done;
}

double ParticleStepper::next_step_end() const {
  return dem_->time() + (coupled_ ? coupled_->substeps() : 1) * dem_->params().dt;
}

Totals ParticleStepper::totals() {
  Totals s;
  EnergyBudget& e = s.energy;
  e = dem_->energy();  // this rank's share: its parcels, a pair with a ghost on the lower id's rank
  e.work_fluid = dem_->fluid_work();
  double v[] = {e.kinetic_translational, e.kinetic_rotational, e.kinetic_rotational_originals, e.potential,
                e.elastic, e.dissipated_damping, e.dissipated_friction, e.work_walls, e.work_fluid,
                e.momentum.x, e.momentum.y, e.momentum.z, e.mass};
  comm().sum(v);
  e.kinetic_translational = v[0], e.kinetic_rotational = v[1], e.kinetic_rotational_originals = v[2];
  e.potential = v[3], e.elastic = v[4], e.dissipated_damping = v[5], e.dissipated_friction = v[6];
  e.work_walls = v[7], e.work_fluid = v[8], e.momentum = {v[9], v[10], v[11]}, e.mass = v[12];
  long n[] = {static_cast<long>(dem_->owned()), dem_->removed()};
  comm().sum(n);
  s.present = n[0], s.removed = n[1];
  return s;
}

const fluid::FluidState& ParticleStepper::whole_air() { return domain_.gather(air_, whole_air_); }

const fluid::Field& ParticleStepper::whole_alpha() { return domain_.gather_cells(fluid_->ibm().alpha_cell, whole_alpha_); }

parallel::PortableState ParticleStepper::portable_state() {
  return comm().gather_state(parallel::portable_state(dem_->particles(), dem_->neighbor_list(), dem_->owned()));
}

RunPosition ParticleStepper::position() {
  RunPosition h;
  h.t = dem_->time(), h.steps = dem_->steps(), h.builds = dem_->neighbor_builds(), h.ranks = comm().size();
  h.removed = comm().sum(dem_->removed());
  const EnergyBudget a = dem_->removed_accounts();
  double v[] = {a.dissipated_damping, a.dissipated_friction, a.work_walls, a.work_fluid};
  comm().sum(v);
  h.removed_damping = v[0], h.removed_friction = v[1], h.removed_walls = v[2], h.removed_fluid = v[3];
  return h;
}

}  // namespace cgdem::run
