// The verification grids here are tiny (<= 8k cells): with the machine shared, OpenMP
// barriers in the pressure solver cost far more than the work. Unless the user chose a
// thread count (OMP_NUM_THREADS), the fluid tests run on one thread. Results do not
// depend on the thread count (checked by running with OMP_NUM_THREADS=2).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdlib>

namespace {

class OneThreadUnlessAsked : public ::testing::Environment {
 public:
  void SetUp() override {
    if (std::getenv("OMP_NUM_THREADS") == nullptr) omp_set_num_threads(1);
  }
};

const auto* const kEnv = ::testing::AddGlobalTestEnvironment(new OneThreadUnlessAsked);

}  // namespace
