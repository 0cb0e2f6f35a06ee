// A run's parcels and air cells over the ranks of an MPI communicator (run::Domain): one
// block of the DEM domain per rank, cut at the quantiles of the parcels' positions
// (parallel::balanced_cuts) and, with air, moved onto the cell faces of the air grid, so
// that each rank steps the parcels and the air cells of one block:
//   * parcels: parallel::DistributedDem, ghost copies of the neighbours' parcels
//     (docs/scale_out.md);
//   * air: HaloSync (halo exchanges, the blocks' boundaries), the distributed pressure
//     solve (air_mpi::DistPressureSolver with the preconditioner of
//     air.pressure.mpi_preconditioner; "auto": additive Schwarz multigrid on up to 4 ranks,
//     hypre's PFMG beyond when the build has it);
//   * the air of the whole grid is gathered on rank 0 for snapshots and checkpoints.
// Results agree with one process to round-off that the granular flow amplifies, not bit
// for bit: a parcel's contact forces are summed in its rank's order, and the pressure
// solve's dot products in another order. Not supported over ranks: periodic axes with air,
// the implicit drag coupling (both refused with a message).
#pragma once
#include <mpi.h>

#include <memory>
#include <optional>

#include "parallel/decomposition.hpp"
#include "parallel/grid_blocks.hpp"
#include "parallel/mpi/halo_sync.hpp"
#include "solvers/dem_mpi/distributed_dem.hpp"
#include "solvers/run/domain.hpp"
#include "solvers/run_mpi/mpi_comm.hpp"

namespace cgdem::run {

class MpiDomain final : public Domain {
 public:
  explicit MpiDomain(MPI_Comm comm);
  ~MpiDomain() override;
  RunComm& comm() override { return comm_; }
  void decompose(const DemSolver& dem, const std::vector<Vec3>& where, const AirSpec* air) override;
  bool owns(const Vec3& x) const override { return d_->owner_of(x) == comm_.rank(); }
  std::unique_ptr<DomainExchange> attach(DemSolver& dem) override;
  AirShare share_air(const AirSpec& air) override;
  const fluid::FluidState& gather(const fluid::FluidState& local, fluid::FluidState& whole) override;
  const fluid::Field& gather_cells(const fluid::Field& local, fluid::Field& whole) override;
  void take(const fluid::FluidState& whole, fluid::FluidState& local) override;
  std::string describe() const override;
  std::string report(const DemSolver& dem, long air_cells) override;

 private:
  MpiComm comm_;
  std::optional<parallel::Decomposition> d_;
  air_mpi::GridBlocks::Starts starts_;  // with air: the blocks' first cells along each axis
  bool with_air_ = false;
  fluid::MacGrid grid_;  // the whole air grid
  std::unique_ptr<air_mpi::GridBlocks> blocks_;
  std::unique_ptr<air_mpi::HaloSync> sync_;
  parallel::DistributedDem* dist_ = nullptr;  // attached to the DEM (owned by its caller)
};

}  // namespace cgdem::run
