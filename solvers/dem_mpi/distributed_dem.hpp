// The DEM step over MPI ranks (issue 6, docs/scale_out.md "Ghost parcels"): each rank runs
// a DemSolver on the parcels of its block, with ghost copies of the neighbouring ranks'
// parcels near it, through the DemSolver's DomainExchange hook.
//
//   * A pair of parcels on two ranks (a split pair) is listed on both, under the owned
//     parcel (ghosts come after the owned parcels, so a ghost is never an owner), and
//     evaluated on both: each rank keeps the force on its own parcel and drops the
//     ghost's. The contact law gives exactly the negated force from the partner's side,
//     so no force comes back from the ghosts' ranks and Newton's third law holds to the
//     bit. Each rank keeps the pair's history in its own parcel's frame (the two are
//     exact negations); its dissipated energy is booked on the rank of the lower id.
//   * Every step without a list build: the ghosts' x, v, omega from their owners, one
//     message with each neighbour that shares ghosts (in the order of the last build).
//   * The rebuild test is a global OR: all ranks build together. At a build: the split
//     pairs' histories become id-keyed records (NeighborList::incoming), the ghosts are
//     dropped, escaped parcels removed (per rank), parcels migrated to their owners
//     (mpi/migrate.hpp: the records of a leaving parcel go with it, and a pair that the
//     migration splits keeps its history on both sides), each rank sends each neighbour
//     copies of its parcels within one interaction range (2 r_max + skin) of that
//     neighbour's block, appends the ones it receives as ghosts and builds; the build
//     attaches the records by id.
//
// Summation order is the only difference from one process (a parcel's contacts are added
// in the order of its rank's lists): results agree to round-off, which a granular flow
// amplifies. On one rank there are no ghosts and the run is the serial one, bit for bit.
//
// Not supported: periodic axes and parcels added between steps (both refused). Ranks may
// run several OpenMP threads each: the force pass gives the same bits for any count.
// Keep the DistributedDem alive as long as its DemSolver steps.
#pragma once
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "core/timers.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/mpi/migrate.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::parallel {

class DistributedDem final : public DomainExchange {
 public:
  // Attaches itself to `dem` (and detaches in the destructor); collective over comm, whose
  // size must be d.ranks(). Give each rank's DemSolver the parcels of its block (or of a
  // neighbouring block: the first build migrates them) before its first step. Throws
  // cgdem::Error for periodic axes or a decomposed box that does not hold the DEM domain
  // (a parcel kept by the domain test must have an owner).
  DistributedDem(MPI_Comm comm, const Decomposition& d, DemSolver& dem);
  ~DistributedDem() override;
  DistributedDem(const DistributedDem&) = delete;
  DistributedDem& operator=(const DistributedDem&) = delete;

  bool any(bool local_rebuild) override;
  void drop_ghosts(Particles& p, NeighborList& nl) override;
  void rebuild(Particles& p, NeighborList& nl, const geometry::Scene::Frame& walls) override;
  void refresh_ghosts(Particles& p) override;
  // One block: no ghosts and no neighbour to migrate to.
  bool relative_rebuild_test() const override { return d_.ranks() == 1; }

  struct Counters {
    long builds = 0;
    long parcels_sent = 0, records_sent = 0;  // by migration, summed over builds (this rank)
    long ghosts_received = 0;                 // at the last build
    long records_split = 0;                   // split-pair histories turned into records, summed
    // Records for the same pair that reached this rank twice (from both of its ranks), and
    // among them those whose histories differ (in value): must stay 0.
    long records_twice = 0, records_differing = 0;
  };
  const Counters& counters() const { return counters_; }
  // This rank's time in the hook's calls (all inside the DEM's "neighbour lists" phase):
  // "rebuild vote" (the global OR: it waits for the slowest rank, so load imbalance shows
  // here), "ghost refresh" (pack, exchange, unpack) and "build exchanges" (drop ghosts,
  // migrate, ghost copies, list build).
  PhaseTimers& timers() { return timers_; }
  int rank() const { return rank_; }
  const Decomposition& decomposition() const { return d_; }
  MPI_Comm comm() const { return comm_; }

 private:
  // Owned parcels within the interaction range of each neighbour's block, in id order.
  void select_ghosts(const Particles& p, size_t n_owned);
  // After the build (which sorted the owned parcels): the ghosts each neighbour holds found
  // again (the same positions and range give the same parcels, in the same id order; a
  // different count is an error), and the buffers of refresh_ghosts() sized.
  void reselect_ghosts(const Particles& p, size_t n_owned);

  MPI_Comm comm_;
  Decomposition d_;
  DemSolver& dem_;
  int rank_ = 0;
  std::vector<int> nb_;                  // neighbour ranks
  double range_ = 0;                     // 2 r_max + skin at the last build
  std::vector<std::vector<int>> send_;   // per neighbour: the owned parcels it holds as ghosts
  std::vector<int> recv_;                // per neighbour: the ghosts it sent (appended in slot order)
  size_t n_owned_ = 0, n_total_ = 0;     // at the last build
  std::vector<std::vector<double>> sbuf_, rbuf_;
  Counters counters_;
  PhaseTimers timers_;
  int t_vote_, t_refresh_, t_build_;
};

// Diagnostics over all ranks (collective over comm; every rank gets the result).
// The energy budget of DemSolver::energy() over the owned parcels of every rank, a split
// pair's elastic energy counted once (and the removed parcels' accounts of every rank).
// work_fluid is left 0, as energy() does (DemSolver::fluid_work()).
EnergyBudget global_energy(MPI_Comm comm, const DemSolver& dem);
long global_contacts(MPI_Comm comm, const DemSolver& dem);  // sum of contact_count()
long global_removed(MPI_Comm comm, const DemSolver& dem);   // sum of removed()
// Pairs of an owned parcel and a ghost in this rank's lists (listed; and overlapping).
struct SplitPairs {
  long listed = 0, touching = 0;
};
SplitPairs split_pairs(const DemSolver& dem);

}  // namespace cgdem::parallel
