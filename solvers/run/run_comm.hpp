// The communicator of a run: what the run driver and its outputs need from the other MPI
// ranks, and nothing else. The single-process run has SerialComm, the identity: sums are
// the values themselves, "gathered" parcels are this process's own (in its own order),
// and an error is thrown as it is. The run over MPI ranks has MpiComm
// (solvers/run_mpi/mpi_comm.hpp). Both are used by the same code, so that one process and
// N ranks run the same sequence of calls (solvers/run/run_driver.hpp).
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <span>

#include "parallel/portable_state.hpp"
#include "particles/particles.hpp"

namespace cgdem::run {

class RunComm {
 public:
  virtual ~RunComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool root() const { return rank() == 0; }

  // Collective. In place: each entry summed over the ranks (every rank gets the sums).
  virtual void sum(std::span<double> v) = 0;
  virtual void sum(std::span<long> v) = 0;
  // Collective: the smallest and the largest of v over the ranks.
  virtual std::array<long, 2> min_max(long v) = 0;
  long sum(long v) {
    sum(std::span<long>(&v, 1));
    return v;
  }
  double sum(double v) {
    sum(std::span<double>(&v, 1));
    return v;
  }

  // Collective: f() on every rank (on rank 0 only when root_only). A cgdem::Error thrown by
  // f on any rank stops every rank here (parallel::RaisedTogether over ranks, carrying the
  // message where it was found), so that no rank is left waiting in a later collective
  // call. `what` names the stage in the message of the ranks that did not fail.
  virtual void together(const char* what, bool root_only, const std::function<void()>& f) = 0;

  // Collective: parcels [0, owned) of every rank, on rank 0 in increasing id (the other
  // ranks get an empty set). Kinematics: only id, species, x, v and radius (what the
  // die-filling diagnostics read). The result stays valid until the next call.
  enum class Fields { All, Kinematics };
  virtual const Particles& gather(const Particles& p, size_t owned, Fields fields) = 0;
  // Collective: the union of the ranks' portable states on rank 0 (the others: empty).
  virtual parallel::PortableState gather_state(const parallel::PortableState& local) = 0;
};

// One process: every collective is the identity.
class SerialComm final : public RunComm {
 public:
  using RunComm::sum;
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void sum(std::span<double>) override {}
  void sum(std::span<long>) override {}
  std::array<long, 2> min_max(long v) override { return {v, v}; }
  void together(const char*, bool, const std::function<void()>& f) override { f(); }
  const Particles& gather(const Particles& p, size_t, Fields) override { return p; }
  parallel::PortableState gather_state(const parallel::PortableState& local) override { return local; }
};

}  // namespace cgdem::run
