// What advances a case with parcels in time, on one process or over MPI ranks: the DEM
// alone (vacuum), or the coupled step of the DEM and the air (solvers/coupled). The
// Domain decides which parcels and cells are this rank's; the steps themselves are the
// solvers', the same calls for one process and for N ranks.
//
// Set-up, collective, in this order (run_checkpoint.hpp does it for a restart):
//   1. place_parcels(): this rank's parcels, from the case as built (every rank builds all
//      of it, with the same seed) or from a checkpoint's state;
//   2. make_air(): the air's solvers on this rank's cells;
//   3. take_air(): a checkpoint's air on them.
// One process keeps the case's parcels in their order and attaches no exchange: it is
// then exactly the run without any of this.
#pragma once
#include <memory>
#include <optional>

#include "fluid/fluid_state.hpp"
#include "parallel/portable_state.hpp"
#include "solvers/coupled/coupled_solver.hpp"
#include "solvers/dem/dem_solver.hpp"
#include "solvers/fluid/fluid_solver.hpp"
#include "solvers/run/domain.hpp"

namespace cgdem::run {

// Where a checkpoint left the run: its position in time, and the totals over the ranks of
// the parcels that had left the domain and of their energy accounts (checkpoints hold it,
// run_checkpoint.hpp).
struct RunPosition {
  double t = 0;
  long steps = 0, removed = 0, builds = 0;
  double removed_damping = 0, removed_friction = 0, removed_walls = 0, removed_fluid = 0;
  int ranks = 1;  // that wrote it (information)
};

// What one step did.
struct StepDone {
  long dem_steps = 0;                       // DEM steps taken
  double dt = 0;                            // its length [s]
  std::optional<CoupledStepStats> coupled;  // with air
};

// Totals over the ranks (every rank gets them).
struct Totals {
  EnergyBudget energy;  // with work_fluid
  long present = 0, removed = 0;
};

class ParticleStepper {
 public:
  // dem: the whole case as built, before its first step; air: none in vacuum.
  ParticleStepper(Domain& domain, std::unique_ptr<DemSolver> dem, std::optional<AirSpec> air);
  ~ParticleStepper();
  ParticleStepper(const ParticleStepper&) = delete;
  ParticleStepper& operator=(const ParticleStepper&) = delete;

  // 1. The case's parcels (a fresh run), or those of a checkpoint's state, from which the
  //    run goes on at `at` (the stored forces kick first; the lists are built at the first
  //    step, attaching the stored histories by id).
  void place_parcels();
  void place_parcels(const parallel::PortableState& s, const RunPosition& at);
  // 2. The air's solvers on this rank's cells (nothing in vacuum).
  void make_air();
  // 3. A checkpoint's air (the whole grid; ghost layers are filled here) on this rank's cells.
  void take_air(const fluid::FluidState& whole);

  // One step, collective: a fluid step with its DEM substeps, or one DEM step in vacuum.
  // Errors of its exchanges are raised on every rank together.
  StepDone step();
  // The time the next step will end (collective with air: its CFL limit is global).
  double next_step_end() const;

  DemSolver& dem() { return *dem_; }
  const DemSolver& dem() const { return *dem_; }
  bool with_air() const { return air_spec_.has_value(); }
  const AirSpec& air_spec() const { return *air_spec_; }
  const AirShare& air_share() const { return share_; }
  fluid::FluidState& air() { return air_; }
  fluid::FluidSolver& fluid() { return *fluid_; }
  CoupledSolver& coupled() { return *coupled_; }
  Domain& domain() { return domain_; }
  RunComm& comm() { return domain_.comm(); }

  // Collective views of the whole run on rank 0 (one process: its own state, not copied).
  Totals totals();
  // The air of the whole grid (interior entries; one process: with its ghost layers).
  const fluid::FluidState& whole_air();
  // The cells' wall fractions on the whole grid (empty before the first fluid step on one process).
  const fluid::Field& whole_alpha();
  // The state of every parcel, rank-independent (parallel/portable_state.hpp).
  parallel::PortableState portable_state();
  // Where the run is, with the totals of the removed parcels' accounts.
  RunPosition position();

 private:
  Domain& domain_;
  std::unique_ptr<DemSolver> dem_;
  std::unique_ptr<DomainExchange> exchange_;  // over ranks: detaches itself from dem_ when destroyed
  std::optional<AirSpec> air_spec_;
  AirShare share_;
  fluid::FluidState air_;
  std::unique_ptr<fluid::FluidSolver> fluid_;
  std::unique_ptr<CoupledSolver> coupled_;
  fluid::FluidState whole_air_;  // gathered (over ranks)
  fluid::Field whole_alpha_;
};

}  // namespace cgdem::run
