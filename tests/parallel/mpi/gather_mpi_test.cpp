// Gathering the ranks' parcels and handing a gathered state out again (mpi/gather.hpp),
// on however many ranks the test runs: a bed handed out to the blocks of one layout,
// gathered, handed out to another layout of the same ranks and gathered again, comes back
// with every parcel bit for bit, in id order, and every history except those of the pairs
// the cuts split (without ghost parcels nobody holds those). Checks are reduced over the
// ranks before they are asserted; only rank 0 prints.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "../mpi_util.hpp"
#include "../parallel_test_util.hpp"
#include "parallel/mpi/gather.hpp"

namespace cgdem::parallel {
namespace {

using test::summed;
using test::world_rank;
using test::world_size;

const Species kS = test::powder_l3();
const double kD = kS.diameter(), kA = 0.98 * kD;

const int kNx = 12, kNy = 6, kNz = 3;
const geometry::Aabb kBox{{0, 0, 0}, {kNx * kA + kD, kNy * kA + kD, kNz * kA + kD}};

// The whole bed with its histories, built the same way on every rank.
PortableState whole_bed(const geometry::Scene& scene) {
  std::vector<int64_t> ids(kNx * kNy * kNz);
  for (size_t k = 0; k < ids.size(); ++k) ids[k] = 5 + 3 * static_cast<int64_t>(k);
  std::shuffle(ids.begin(), ids.end(), std::mt19937(11));
  Particles p;
  size_t n = 0;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i)
        test::add_distinct(p, ids[n++], Vec3{0.5 * kD, 0.5 * kD, 0.99 * 0.5 * kD} + kA * Vec3{double(i), double(j), double(k)}, kS);
  NeighborList nl;
  nl.skin = 0.1 * kD;
  nl.build(p, scene.at(0));
  test::set_histories(p, nl);
  return portable_state(p, nl);
}

// Hands `all` (significant on rank 0) out to layout d, builds, gathers on rank 0.
PortableState round_trip(const Decomposition& d, const PortableState& all, const geometry::Scene& scene,
                         long& misplaced) {
  Particles p;
  NeighborList nl;
  nl.skin = 0.1 * kD;
  scatter_state(MPI_COMM_WORLD, d, all, p, nl);
  nl.build(p, scene.at(0));
  long wrong = 0;
  for (size_t i = 0; i < p.size(); ++i) wrong += d.owner_of(p.x[i]) != world_rank();
  misplaced = summed(wrong);
  return gather_state(MPI_COMM_WORLD, portable_state(p, nl));
}

long split_pairs(const PortableState& s, const Decomposition& d) {
  auto at = [&](int64_t id) { return s.p.x[std::lower_bound(s.p.id.begin(), s.p.id.end(), id) - s.p.id.begin()]; };
  long n = 0;
  for (const CarriedPair& c : s.pairs) n += d.owner_of(at(c.id_a)) != d.owner_of(at(c.id_b));
  return n;
}

TEST(Gather, ParcelsComeBackInIdOrderBitForBitThroughTwoLayouts) {
  const int size = world_size(), rank = world_rank();
  const geometry::Scene scene = test::floor_scene();
  const PortableState all = whole_bed(scene);
  // Two layouts of the same ranks: the chosen one, and all cuts along y instead.
  const Decomposition d1(kBox, choose_dims(size, kBox.hi - kBox.lo));
  const Decomposition d2(kBox, {1, size, 1});
  long misplaced1 = 0, misplaced2 = 0;
  const PortableState g1 = round_trip(d1, rank == 0 ? all : PortableState{}, scene, misplaced1);
  const PortableState g2 = round_trip(d2, g1, scene, misplaced2);
  long ok = 1;
  if (rank == 0) {
    long differ = 0;
    for (size_t i = 0; i < std::min(g2.size(), all.size()); ++i)
      differ += test::bytes_of(g2.p, i) != test::bytes_of(all.p, i);
    const long split1 = split_pairs(all, d1), split2 = split_pairs(g1, d2);
    std::printf("[ gather ] %d ranks, layouts %dx%dx%d then 1x%dx1: %zu -> %zu -> %zu parcels (%ld differ bitwise), "
                "pair histories %zu -> %zu -> %zu (split by the cuts: %ld, then %ld), wall %zu -> %zu\n",
                size, d1.dims()[0], d1.dims()[1], d1.dims()[2], size, all.size(), g1.size(), g2.size(), differ,
                all.pairs.size(), g1.pairs.size(), g2.pairs.size(), split1, split2, all.walls.size(), g2.walls.size());
    ok = g2.size() == all.size() && differ == 0 && std::is_sorted(g2.p.id.begin(), g2.p.id.end()) &&
         static_cast<long>(g1.pairs.size()) == static_cast<long>(all.pairs.size()) - split1 &&
         static_cast<long>(g2.pairs.size()) == static_cast<long>(g1.pairs.size()) - split2 &&
         g2.walls.size() == all.walls.size() && (size == 1 ? split1 == 0 : split1 > 0);
  } else {
    ok = g1.size() == 0 && g2.size() == 0;  // only the root receives
  }
  EXPECT_EQ(misplaced1, 0);
  EXPECT_EQ(misplaced2, 0);
  EXPECT_EQ(summed(ok), size);
}

}  // namespace
}  // namespace cgdem::parallel
