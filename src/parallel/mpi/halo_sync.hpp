// fluid::FieldSync for one block of the air grid per MPI rank (fluid/field_sync.hpp): the
// boundary fills of boundary.hpp on the block's physical sides, the halo exchange of halo.hpp
// on its cut sides, reductions over the communicator, errors raised on every rank together
// (parallel::raise_together). With it, a FluidSolver and a coupling::Exchange built on the
// block's grid and boundary (local_boundary) step their block of the whole grid.
#pragma once
#include <mpi.h>

#include "parallel/mpi/halo.hpp"
#include "fluid/field_sync.hpp"

namespace cgdem::air_mpi {

class HaloSync final : public fluid::FieldSync {
 public:
  // global: the whole grid; global_bc: its boundary conditions (no periodic side).
  // Collective over comm (size blocks.ranks()).
  HaloSync(MPI_Comm comm, const GridBlocks& blocks, const fluid::MacGrid& global, const fluid::FluidBoundary& global_bc);

  void fill_scalar(fluid::Field& s, fluid::ScalarKind kind) override;
  void fill_velocity(fluid::Field& u, fluid::Field& v, fluid::Field& w) override;
  void fill_velocity_component(int d, fluid::Field& f) override;
  void copy_ghosts(fluid::Field& f, int stagger) override;
  void sum_deposits(fluid::Field& f, int stagger) override;
  bool is_cut(int side) const override { return halo_.blocks().is_cut(side); }
  void max(double* v, int n) override;
  double sum(double v) override;
  long sum(long v) override;
  bool any(bool v) override;
  void raise_if(bool failed, const std::string& message) override;

  const fluid::MacGrid& local_grid() const { return local_; }
  // The boundary conditions of the block (cut sides Open), for its solvers' parameters.
  const fluid::FluidBoundary& local_bc() const { return local_bc_; }
  const GridBlocks& blocks() const { return halo_.blocks(); }
  Halo& halo() { return halo_; }

 private:
  Halo halo_;
  fluid::MacGrid local_;
  fluid::FluidBoundary global_bc_, local_bc_;
  int rank_ = 0;
};

}  // namespace cgdem::air_mpi
