// Small helpers of the multi-rank tests (one process per rank, MPI_COMM_WORLD): this rank,
// the rank count, and reductions of a check's value over the ranks, so that every rank
// asserts the same result.
#pragma once
#include <mpi.h>

#include <type_traits>

namespace cgdem::test {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int world_size() {
  int s = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}
// v reduced with op over the ranks (long or double).
template <class T>
T reduced(T v, MPI_Op op) {
  static_assert(std::is_same_v<T, long> || std::is_same_v<T, double>);
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, std::is_same_v<T, double> ? MPI_DOUBLE : MPI_LONG, op, MPI_COMM_WORLD);
  return v;
}
inline long summed(long v) { return reduced(v, MPI_SUM); }
inline double maxed(double v) { return reduced(v, MPI_MAX); }

}  // namespace cgdem::test
