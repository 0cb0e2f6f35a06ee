// Air fields gathered from the blocks into the whole grid and handed out again
// (parallel/mpi/field_gather.hpp): cell fields and the three face fields, on 1, 2 and 4 ranks
// (2 x 2 x 1 and 4 x 1 x 1), bitwise, every interior entry once.
#include <gtest/gtest.h>

#include <cstdio>

#include "parallel/mpi/field_gather.hpp"
#include "mpi_air_util.hpp"

namespace cgdem::air_mpi {
namespace {

// A value no other entry (or stagger) shares.
double value(int x, int y, int z, int stagger) { return 1e4 * x + 1e2 * y + z + 0.25 * (stagger + 1); }

TEST(AirFieldGather, BlocksMakeTheGlobalFieldAndBack) {
  const std::array<int, 3> n{12, 10, 7};
  long wrong_gather = 0, wrong_scatter = 0, unowned_set = 0, checked = 0;
  for (const GridBlocks& b : test::layouts(n)) {
    for (int stagger : {-1, 0, 1, 2}) {
      std::array<int, 3> ge = n, le = b.local_cells();
      if (stagger >= 0) ++ge[stagger], ++le[stagger];
      // The block's field: every local entry, except that the face on an upper cut (the
      // upper block's) holds a poison value, which the gather must not pick up.
      auto on_upper_cut = [&](int x, int y, int z) {
        return stagger >= 0 && (stagger == 0 ? x : stagger == 1 ? y : z) == le[stagger] - 1 &&
               b.is_cut(2 * stagger + 1);
      };
      fluid::Field local(le);
      for (int z = 0; z < le[2]; ++z)
        for (int y = 0; y < le[1]; ++y)
          for (int x = 0; x < le[0]; ++x)
            local(x, y, z) = on_upper_cut(x, y, z) ? -1.0 : value(b.lo()[0] + x, b.lo()[1] + y, b.lo()[2] + z, stagger);
      const fluid::Field g = gather_field(MPI_COMM_WORLD, b, local, stagger);
      if (b.rank() == 0) {
        for (int z = 0; z < ge[2]; ++z)
          for (int y = 0; y < ge[1]; ++y)
            for (int x = 0; x < ge[0]; ++x, ++checked) wrong_gather += g(x, y, z) != value(x, y, z, stagger);
      }
      fluid::Field back;
      scatter_field(MPI_COMM_WORLD, b, g, back, stagger);
      for (int z = 0; z < le[2]; ++z)
        for (int y = 0; y < le[1]; ++y)
          for (int x = 0; x < le[0]; ++x) {
            if (on_upper_cut(x, y, z))
              unowned_set += back(x, y, z) != 0;  // the upper block's face: not this block's to receive
            else
              wrong_scatter += back(x, y, z) != local(x, y, z);
          }
    }
  }
  wrong_scatter = test::summed(wrong_scatter);
  unowned_set = test::summed(unowned_set);
  if (test::world_rank() == 0)
    std::printf("[ gather ] %d rank(s): %ld global entries checked, %ld differ after the gather; after the scatter "
                "%ld owned entries differ, %ld cut faces set\n",
                test::world_size(), checked, wrong_gather, wrong_scatter, unowned_set);
  EXPECT_EQ(test::summed(wrong_gather), 0);
  EXPECT_GT(test::summed(checked), 0);
  EXPECT_EQ(wrong_scatter, 0);
  EXPECT_EQ(unowned_set, 0);
}

}  // namespace
}  // namespace cgdem::air_mpi
