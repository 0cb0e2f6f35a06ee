// The run's communicator over the ranks of an MPI communicator (run::RunComm): sums and
// extremes by MPI_Allreduce, errors raised on every rank together (parallel::raise_together),
// parcels and portable states gathered on rank 0 (parallel/mpi/gather.hpp).
#pragma once
#include <mpi.h>

#include "solvers/run/run_comm.hpp"

namespace cgdem::run {

class MpiComm final : public RunComm {
 public:
  explicit MpiComm(MPI_Comm comm);
  using RunComm::sum;
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void sum(std::span<double> v) override;
  void sum(std::span<long> v) override;
  std::array<long, 2> min_max(long v) override;
  void together(const char* what, bool root_only, const std::function<void()>& f) override;
  const Particles& gather(const Particles& p, size_t owned, Fields fields) override;
  parallel::PortableState gather_state(const parallel::PortableState& local) override;
  MPI_Comm comm() const { return comm_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  Particles gathered_;
};

}  // namespace cgdem::run
