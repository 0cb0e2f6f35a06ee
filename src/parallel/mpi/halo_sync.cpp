// HaloSync: see halo_sync.hpp.
#include "parallel/mpi/halo_sync.hpp"

#include "parallel/mpi/exchange.hpp"

namespace cgdem::air_mpi {

HaloSync::HaloSync(MPI_Comm comm, const GridBlocks& blocks, const fluid::MacGrid& global,
                   const fluid::FluidBoundary& global_bc)
    : halo_(comm, blocks), local_(blocks.local_grid(global)), global_bc_(global_bc),
      local_bc_(local_boundary(blocks, global_bc)) {
  MPI_Comm_rank(comm, &rank_);
}

void HaloSync::fill_scalar(fluid::Field& s, fluid::ScalarKind kind) {
  air_mpi::fill_scalar(halo_, local_, global_bc_, s, kind);
}

void HaloSync::fill_velocity(fluid::Field& u, fluid::Field& v, fluid::Field& w) {
  air_mpi::fill_velocity(halo_, local_, global_bc_, u, v, w);
}

void HaloSync::fill_velocity_component(int d, fluid::Field& f) {
  fluid::fill_velocity_component_ghosts(local_, local_bc_, d, f);
  halo_.exchange(f, d);
}

void HaloSync::copy_ghosts(fluid::Field& f, int stagger) {
  if (!f.empty()) halo_.exchange(f, stagger);
}

void HaloSync::sum_deposits(fluid::Field& f, int stagger) {
  halo_.reverse_add(f, stagger);
  halo_.exchange(f, stagger);
}

void HaloSync::max(double* v, int n) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, halo_.comm()), "MPI_Allreduce",
                      "air maximum");
}

double HaloSync::sum(double v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, halo_.comm()), "MPI_Allreduce",
                      "air sum");
  return v;
}

long HaloSync::sum(long v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_SUM, halo_.comm()), "MPI_Allreduce",
                      "air sum");
  return v;
}

bool HaloSync::any(bool v) {
  int x = v ? 1 : 0;
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT, MPI_LOR, halo_.comm()), "MPI_Allreduce", "air vote");
  return x != 0;
}

void HaloSync::raise_if(bool failed, const std::string& message) {
  parallel::raise_together(halo_.comm(), rank_, failed ? message : std::string(), "air step");
}

}  // namespace cgdem::air_mpi
