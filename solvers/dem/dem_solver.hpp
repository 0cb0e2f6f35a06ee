// The coarse-grained DEM time stepper (paper eqs. 1-7, 15-17).
//
// One step of velocity Verlet (translation and rotation of spheres):
//   v^{n+1/2} = v^n + dt/2 F^n/m,      w^{n+1/2} = w^n + dt/2 T^n/I
//   x^{n+1}   = x^n + dt v^{n+1/2}
//   rebuild neighbour lists if some particle (or wall) moved more than skin/2
//   F^{n+1}   = contacts(x^{n+1}, v^{n+1/2}, w^{n+1/2}) + walls + m g + f_ext
//   v^{n+1}   = v^{n+1/2} + dt/2 F^{n+1}/m,  w^{n+1} likewise.
// With air (enable_air_forces) each half kick treats the drag implicitly (backward Euler
// over the half step, unconditionally stable for any drag relaxation time):
//   v' = (v + h/m (F + c u_f)) / (1 + h c/m),  F = contacts + walls + m g + f_ext,
// c = Particles::drag, u_f = Particles::u_fluid, held fixed by the coupling over a fluid step.
// Contact forces follow the case's contact law (contact/laws.hpp: the linear law of the
// paper by default) with the pair parameters of its LawTable; particle-wall contacts use
// each wall part's signed distance (eq. 16) and the wall's own velocity in the relative
// velocity.
#pragma once
#include <array>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "contact/laws.hpp"
#include "io/archive.hpp"
#include "core/timers.hpp"
#include "geometry/scene.hpp"
#include "particles/neighbor_list.hpp"
#include "particles/particles.hpp"

namespace cgdem {

struct DemParams {
  double dt = 1e-6;           // [s]
  Vec3 gravity{0, 0, -9.81};  // [m/s^2]
  double skin = 0;            // neighbour skin [m]; 0 -> 0.1 x largest diameter
  geometry::Aabb domain;      // particles leaving it are removed and counted
  // Periodic axes: the domain is the period box on them (positions wrap, nothing is removed).
  std::array<bool, 3> periodic{false, false, false};
  // The contact energy accounts (dissipated by the dashpots and by friction, work of the
  // walls; output.energy_accounts): false drops them for speed. The motion is the same to
  // the last bit; energy() then gives NaN for what it did not compute.
  bool accounts = true;
};

// Totals over all particles (and those removed), summed in a fixed order.
struct EnergyBudget {
  double kinetic_translational = 0, kinetic_rotational = 0, potential = 0;
  // Rotational energy of the l^3 originals the parcels stand for, each spinning at the
  // parcel's omega (the paper's assumption): l^3 * 1/2 I_O w^2 = (1/2 I w^2) / l^2 by
  // eq. (5), I = l^5 I_O. Not part of balance(): the parcel's own 1/2 I w^2 is what the
  // contact torques work on.
  double kinetic_rotational_originals = 0;
  double elastic = 0;              // stored in contact springs (normal + tangential)
  double dissipated_damping = 0;   // by the normal dashpots, since t = start
  double dissipated_friction = 0;  // tangential dashpot and sliding
  double work_walls = 0;           // done on the particles by moving walls
  double work_fluid = 0;           // done on the particles by the air (drag, pressure force)
  Vec3 momentum;
  double mass = 0;
  // Should stay constant: E_kin + E_pot + E_el + dissipated - wall work.
  double balance() const {
    return kinetic_translational + kinetic_rotational + potential + elastic + dissipated_damping +
           dissipated_friction - work_walls - work_fluid;
  }
};

// What a run over several MPI ranks adds to the step (issue 6): the lists become global,
// and ghost parcels stand for the neighbouring ranks' parcels. DemSolver stays free of
// MPI; the implementation is parallel::DistributedDem (solvers/dem_mpi/distributed_dem.hpp).
// With a hook attached, the particles are this rank's owned parcels followed by
// NeighborList::ghosts ghost copies; the step kicks and drifts only the owned ones.
struct DomainExchange {
  virtual ~DomainExchange() = default;
  // The rebuild decision of every rank, from this rank's (a global OR).
  virtual bool any(bool local_rebuild) = 0;
  // At a list build, before the escaped parcels are removed: keeps the histories of the
  // pairs with a ghost as id-keyed records and removes the ghosts (p and nl then hold the
  // owned parcels only).
  virtual void drop_ghosts(Particles& p, NeighborList& nl) = 0;
  // Then: moves parcels to their owners, appends the new ghosts and builds nl.
  virtual void rebuild(Particles& p, NeighborList& nl, const geometry::Scene::Frame& walls) = 0;
  // Every step without a build, after the drift: the ghosts' x, v, omega from their owners.
  virtual void refresh_ghosts(Particles& p) = 0;
  // Whether the lists may be kept by the test of relative displacements
  // (NeighborList::needs_rebuild): only without ghost layers and migration to keep up, that
  // is on a single block; a run on one rank then takes the steps a run without the hook takes.
  virtual bool relative_rebuild_test() const { return false; }
};

class DemSolver {
 public:
  // `material`: the contact law and its parameters (a MaterialParams is the linear law).
  DemSolver(std::vector<Species> species, const contact::ContactModel& material, const DemParams& params,
            geometry::Scene scene);

  // Particles are added before the first step (or between steps; the lists are rebuilt).
  Particles& particles() { return p_; }
  const Particles& particles() const { return p_; }
  const std::vector<Species>& species() const { return species_; }
  const geometry::Scene& scene() const { return scene_; }
  // The contact law's name (its registry row) and its parameter table (throws Error when
  // the solver runs another law).
  std::string_view contact_law() const { return contact::law_name(tables_); }
  template <class Law>
  const contact::LawTable<Law>& contact_table() const {
    if (const auto* t = std::get_if<contact::LawTable<Law>>(&tables_)) return *t;
    throw Error(std::string("DemSolver: the contact law is ").append(contact_law()).append(", not the one asked for"));
  }
  const DemParams& params() const { return params_; }

  void set_time(double t) { t_ = t; }
  double time() const { return t_; }
  long steps() const { return steps_; }
  void step();
  // n steps (as n calls of step(), to the bit), the kicks between two of them in one pass
  // over the particles: for callers that look at the particles only after the n-th.
  void advance(long n);

  // This process's share: its owned parcels (all of them without a DomainExchange), a pair
  // with a ghost counted on the rank of its lower id; over MPI ranks
  // parallel::global_energy() (distributed_dem.hpp) sums the shares.
  EnergyBudget energy() const;
  // Work done on the particles by drag and f_ext since the start (kept per particle, summed
  // in a fixed order; includes removed particles).
  double fluid_work() const;
  // Air forces: when on, the kick integrates the linear drag drag (u_fluid - v) implicitly
  // (Particles::drag, u_fluid set by the coupling), adds the drag impulse to j_drag and
  // books its work and f_ext's in w_fluid.
  void enable_air_forces(bool on) { air_forces_ = on; }
  long removed() const { return removed_; }      // particles that left the domain
  // The energy accounts of the removed particles (dissipated_damping, dissipated_friction,
  // work_walls, work_fluid; the other fields 0), which energy() adds to its totals.
  EnergyBudget removed_accounts() const;
  long neighbor_builds() const { return nl_.builds; }
  size_t pair_entries() const { return nl_.pair_entries(); }
  // Number of particle-particle contacts (pairs with overlap) and wall contacts. With
  // ghosts, the owned parcels' contacts, a pair with a ghost counted on the rank of its
  // lower id (the sum over ranks is the global count).
  long contact_count() const;
  // MPI runs (DomainExchange above): the hook, not owned (nullptr: the serial run, which
  // is then exactly what it is without this). Attach it before the first step.
  void set_domain_exchange(DomainExchange* x) { exchange_ = x; }
  DomainExchange* domain_exchange() const { return exchange_; }
  // Parcels of this rank (not ghosts): particles()[0 .. owned() - 1].
  size_t owned() const { return nl_.owned(p_); }
  const NeighborList& neighbor_list() const { return nl_; }
  const geometry::Scene::Frame& frame() const { return frame_; }
  PhaseTimers& timers() { return timers_; }
  // Checkpoint: the complete state (particles in their current order, neighbour lists with
  // contact history, time, counters, energy accounts), so that a run continued from it is
  // bit-identical to one that never stopped (dem_checkpoint.cpp). load() expects a solver
  // built from the same case (species, material, walls).
  void save(io::ArchiveWriter& w) const;
  void load(io::ArchiveReader& r);
  // The lists held now may be incomplete for this solver's skin (loaded from a run with
  // another skin or other parcel sizes): the next step rebuilds them before it evaluates a
  // contact. Forces already computed stay valid.
  void rebuild_lists_at_next_step() { nl_.x_at_build.clear(); }
  // Continues a run from a state handed out parcel by parcel (a checkpoint written on any
  // number of MPI ranks, parallel/portable_state.hpp): the particles become `parcels`,
  // whose force and torque are those of the checkpoint's step, `histories` wait in
  // NeighborList::incoming, and the time, step count and removed parcels' totals are set.
  // The next step kicks with the stored forces and builds the lists first (attaching the
  // histories by id), as the run that wrote the checkpoint went on; only the order of the
  // force sums may differ from it.
  void resume(double t, long steps, long removed, const EnergyBudget& removed_accounts, Particles parcels,
              NeighborList::Incoming histories);
  // Smallest collision time over all species pairs and walls.
  double min_collision_time() const {
    return std::visit([](const auto& t) { return t.min_collision_time(); }, tables_);
  }

 private:
  void kick(double half_dt);
  void compute_forces();
  void remove_escaped();
  void rebuild_lists();
  template <class Law>
  double elastic_energy(const contact::LawTable<Law>& table) const;
  // The section tag of save(): "dem" for the default law (the format before the registry),
  // "dem/NAME" for another, so that a checkpoint is not continued under another law.
  std::string checkpoint_tag() const;

  std::vector<Species> species_;
  contact::ContactTables tables_;
  DemParams params_;
  geometry::Scene scene_;
  geometry::Scene::Frame frame_;
  Particles p_;
  NeighborList nl_;
  double t_ = 0;
  long steps_ = 0;
  long removed_ = 0;
  bool forces_valid_ = false;
  bool air_forces_ = false;
  // Energy totals of particles that were removed (their per-particle accounts).
  double removed_damping_ = 0, removed_friction_ = 0, removed_walls_ = 0, removed_fluid_ = 0;
  PhaseTimers timers_;
  int t_kick_, t_drift_, t_neigh_, t_force_;
  DomainExchange* exchange_ = nullptr;
};

}  // namespace cgdem
