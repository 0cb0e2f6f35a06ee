#include "solvers/run_mpi/mpi_comm.hpp"

#include "core/error.hpp"
#include "parallel/mpi/exchange.hpp"
#include "parallel/mpi/gather.hpp"

namespace cgdem::run {

MpiComm::MpiComm(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
}

void MpiComm::sum(std::span<double> v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm_),
                      "MPI_Allreduce", "run");
}

void MpiComm::sum(std::span<long> v) {
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_LONG, MPI_SUM, comm_),
                      "MPI_Allreduce", "run");
}

std::array<long, 2> MpiComm::min_max(long v) {
  long r[2] = {-v, v};
  parallel::check_mpi(MPI_Allreduce(MPI_IN_PLACE, r, 2, MPI_LONG, MPI_MAX, comm_), "MPI_Allreduce", "run");
  return {-r[0], r[1]};
}

void MpiComm::together(const char* what, bool root_only, const std::function<void()>& f) {
  std::string error;
  if (!root_only || rank_ == 0) {
    try {
      f();
    } catch (const Error& e) {
      error = e.what();
    }
  }
  parallel::raise_together(comm_, rank_, error, what);
}

const Particles& MpiComm::gather(const Particles& p, size_t owned, Fields fields) {
  gathered_ = fields == Fields::All ? parallel::gather_particles(comm_, p, owned)
                                    : parallel::gather_kinematics(comm_, p, owned);
  return gathered_;
}

parallel::PortableState MpiComm::gather_state(const parallel::PortableState& local) {
  return parallel::gather_state(comm_, local);
}

}  // namespace cgdem::run
