// How the parcels and the air cells of a run are shared among the processes that step it.
// One process (SerialDomain) holds all of them: every call below is the identity or does
// nothing. Over MPI ranks (MpiDomain, solvers/run_mpi/mpi_domain.hpp) each rank holds one
// block of the DEM domain, with ghost parcels from its neighbours (parallel::DistributedDem)
// and the air cells of the same block (HaloSync, the distributed pressure solve).
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "coupling/exchange.hpp"
#include "fluid/field_sync.hpp"
#include "fluid/fluid_state.hpp"
#include "solvers/coupled/coupled_solver.hpp"
#include "solvers/dem/dem_solver.hpp"
#include "solvers/pressure/pressure_solver.hpp"
#include "solvers/run/run_comm.hpp"

namespace cgdem::run {

// The air of a case as its reader gives it: the whole grid.
struct AirSpec {
  fluid::MacGrid grid;
  fluid::FluidParams fluid;
  CoupledParams coupled;
  coupling::ExchangeParams exchange;
  // The distributed pressure solve's preconditioner over ranks (air.pressure.mpi_preconditioner).
  std::string mpi_preconditioner = "auto";
};

// This rank's share of the air: its cells, and what its solvers need to treat them as a
// block of the whole grid.
struct AirShare {
  fluid::MacGrid grid;                                 // this rank's cells (one process: all)
  fluid::FluidParams fluid;                            // boundary with the cut sides marked
  coupling::ExchangeParams exchange;                   // the same boundary
  std::unique_ptr<pressure::PressureSolver> pressure;  // null: the solver FluidParams names
  fluid::FieldSync* sync = nullptr;                    // null: the air solver's own (one process)
  std::array<int, 3> first_cell{};                     // this block's first cell in the whole grid
  std::string pressure_text;                           // for the banner: "pressure pcg-mg2"
};

class Domain {
 public:
  virtual ~Domain() = default;
  virtual RunComm& comm() = 0;

  // Set-up, collective, in this order.
  // Cuts the DEM domain into one block per rank, shared out evenly over the parcels at
  // `where` (the case's, or a checkpoint's), on cell faces of the air grid when there is
  // air. Throws ConfigError for what a decomposition cannot run (periodic axes with air,
  // a neighbour-list skin wider than a cell, too few cells for the blocks).
  virtual void decompose(const DemSolver& dem, const std::vector<Vec3>& where, const AirSpec* air) = 0;
  // Whether a parcel at x belongs to this rank.
  virtual bool owns(const Vec3& x) const = 0;
  // Once dem holds this rank's parcels: the exchange of ghost parcels, attached to dem
  // (null for one process). The caller keeps it while dem steps.
  virtual std::unique_ptr<DomainExchange> attach(DemSolver& dem) = 0;
  // This rank's air cells and their solvers' parts.
  virtual AirShare share_air(const AirSpec& air) = 0;

  // Collective: the air of this rank's cells assembled into the whole grid's on rank 0
  // (interior entries), into `whole`; one process returns `local` itself, ghost layers
  // included, and copies nothing.
  virtual const fluid::FluidState& gather(const fluid::FluidState& local, fluid::FluidState& whole) = 0;
  // The same for a field of cell values (empty on one process before its first fluid step;
  // over ranks an empty field counts as zeros).
  virtual const fluid::Field& gather_cells(const fluid::Field& local, fluid::Field& whole) = 0;
  // This rank's entries (interior cells and faces) of the air of the whole grid; the ghost
  // layers are left to the boundary fills.
  virtual void take(const fluid::FluidState& whole, fluid::FluidState& local) = 0;

  // The banner's line about the ranks ("" for one process).
  virtual std::string describe() const = 0;
  // Collective: the report's lines about the ranks: exchange times, the parcels and air
  // cells per rank ("" for one process).
  virtual std::string report(const DemSolver& dem, long air_cells) = 0;
};

class SerialDomain final : public Domain {
 public:
  RunComm& comm() override { return comm_; }
  void decompose(const DemSolver&, const std::vector<Vec3>&, const AirSpec*) override {}
  bool owns(const Vec3&) const override { return true; }
  std::unique_ptr<DomainExchange> attach(DemSolver&) override { return nullptr; }
  AirShare share_air(const AirSpec& air) override;
  const fluid::FluidState& gather(const fluid::FluidState& local, fluid::FluidState&) override { return local; }
  const fluid::Field& gather_cells(const fluid::Field& local, fluid::Field&) override { return local; }
  void take(const fluid::FluidState& whole, fluid::FluidState& local) override { local = whole; }
  std::string describe() const override { return {}; }
  std::string report(const DemSolver&, long) override { return {}; }

 private:
  SerialComm comm_;
};

}  // namespace cgdem::run
