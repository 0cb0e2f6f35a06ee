// The main() of the multi-rank test executables (tests/parallel/mpi, tests/parallel/mpi_air):
// GoogleTest inside MPI_Init / MPI_Finalize. Only rank 0 prints the usual report; the other
// ranks print one line per failed check. Every test reduces its checks over the ranks, so
// all ranks pass or fail together, and the exit code is the worst rank's.
#pragma once
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>

namespace cgdem::test {

class FailuresOnly : public ::testing::EmptyTestEventListener {
 public:
  explicit FailuresOnly(int rank) : rank_(rank) {}
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (r.failed())
      std::printf("[ rank %d ] %s:%d: failure\n%s\n", rank_, r.file_name() ? r.file_name() : "?", r.line_number(),
                  r.summary());
  }

 private:
  int rank_;
};

inline int run_tests_on_ranks(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new FailuresOnly(rank));
  }
  int failed = RUN_ALL_TESTS();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return failed;
}

}  // namespace cgdem::test
