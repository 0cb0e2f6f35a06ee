// The rank-independent DEM state (portable_state.hpp): parcels in id order with id-keyed
// histories survive the archive bit for bit, and handing a state out to the blocks of a
// decomposition and taking it back loses only the pairs that the cuts split (which, in a
// run with ghost parcels, the ghost entries hold).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>

#include "../error_of.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/portable_state.hpp"
#include "parallel_test_util.hpp"

namespace cgdem::parallel {
namespace {

const Species kS = test::powder_l3();
const double kD = kS.diameter(), kA = 0.98 * kD;  // lattice spacing: 2 % overlap

// An 8 x 5 x 3 lattice pressed on the floor z = 0, ids shuffled, every pair and wall
// contact with a distinct non-empty history.
struct Bed {
  Particles p;
  NeighborList nl;
  geometry::Scene scene = test::floor_scene();
  Bed() {
    std::vector<int64_t> ids(8 * 5 * 3);
    for (size_t k = 0; k < ids.size(); ++k) ids[k] = 1000 + 7 * static_cast<int64_t>(k);
    std::shuffle(ids.begin(), ids.end(), std::mt19937(5));
    size_t n = 0;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 8; ++i)
          test::add_distinct(p, ids[n++], Vec3{0.99 * 0.5 * kD, 0.5 * kD, 0.99 * 0.5 * kD} + kA * Vec3{double(i), double(j), double(k)}, kS);
    nl.skin = 0.1 * kD;
    nl.build(p, scene.at(0));
    test::set_histories(p, nl);
  }
  geometry::Aabb box() const { return {{0, 0, 0}, {8 * kA + kD, 5 * kA + kD, 3 * kA + kD}}; }
};

bool same_parcels(const Particles& a, const Particles& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (test::bytes_of(a, i) != test::bytes_of(b, i)) return false;
  return true;
}

TEST(PortableState, ArchiveRoundTripIsBitwiseAndInIdOrder) {
  Bed bed;
  const PortableState s = portable_state(bed.p, bed.nl);
  io::ArchiveWriter w;
  save(w, s);
  io::ArchiveReader r(w.bytes(), "test");
  PortableState t;
  load(r, t);
  long pairs_differ = 0, walls_differ = 0;
  for (size_t k = 0; k < std::min(s.pairs.size(), t.pairs.size()); ++k)
    pairs_differ += std::memcmp(&s.pairs[k], &t.pairs[k], sizeof(CarriedPair)) != 0;
  for (size_t k = 0; k < std::min(s.walls.size(), t.walls.size()); ++k)
    walls_differ += std::memcmp(&s.walls[k], &t.walls[k], sizeof(CarriedWall)) != 0;
  std::printf("[ state ] %zu parcels, %zu pair and %zu wall histories (lists: %zu entries, %zu wall candidates); "
              "after the archive: %ld pair and %ld wall records differ\n",
              s.size(), s.pairs.size(), s.walls.size(), bed.nl.hist.size(), bed.nl.wall_hist.size(), pairs_differ,
              walls_differ);
  EXPECT_EQ(s.size(), bed.p.size());
  EXPECT_TRUE(std::is_sorted(s.p.id.begin(), s.p.id.end()));
  EXPECT_EQ(s.pairs.size(), bed.nl.hist.size());  // every entry has a non-empty history here
  EXPECT_EQ(s.walls.size(), 8u * 5u);             // the bottom layer touches the floor
  EXPECT_TRUE(same_parcels(s.p, t.p));
  EXPECT_EQ(t.pairs.size(), s.pairs.size());
  EXPECT_EQ(pairs_differ + walls_differ, 0);
  // Each record is the lists' history in the lower id's frame.
  long wrong = 0;
  for (const CarriedPair& c : s.pairs) wrong += !test::same_bits(c.h, test::pair_history(c.id_a, c.id_b));
  EXPECT_EQ(wrong, 0);
}

TEST(PortableState, HandedToThreeBlocksAndBackLosesOnlyTheSplitPairs) {
  Bed bed;
  const PortableState s = portable_state(bed.p, bed.nl);
  const Decomposition d(bed.box(), {3, 1, 1}, {false, false, false});
  std::vector<PortableState> parts;
  size_t taken = 0;
  for (int r = 0; r < d.ranks(); ++r) {
    Particles p;
    NeighborList nl;
    nl.skin = bed.nl.skin;
    taken += restore(s, [&](const Vec3& x) { return d.owner_of(x) == r; }, p, nl);
    nl.build(p, bed.scene.at(0));  // attaches the queued histories by id
    parts.push_back(portable_state(p, nl));
  }
  const PortableState back = merge(std::move(parts));
  // The pairs the cuts split, from the original lists.
  long split = 0;
  for (const CarriedPair& c : s.pairs) {
    const auto at = [&](int64_t id) {
      const auto it = std::lower_bound(s.p.id.begin(), s.p.id.end(), id);
      return s.p.x[it - s.p.id.begin()];
    };
    split += d.owner_of(at(c.id_a)) != d.owner_of(at(c.id_b));
  }
  long differ = 0;
  size_t k = 0;
  for (const CarriedPair& c : back.pairs) {  // a subsequence of s.pairs, equal bitwise
    while (k < s.pairs.size() && (s.pairs[k].id_a != c.id_a || s.pairs[k].id_b != c.id_b)) ++k;
    differ += k == s.pairs.size() || !test::same_bits(s.pairs[k].h, c.h);
  }
  std::printf("[ blocks ] %zu parcels to 3 blocks and back; pair histories %zu -> %zu (%ld split by the cuts), wall "
              "%zu -> %zu; %ld kept records differ\n",
              taken, s.pairs.size(), back.pairs.size(), split, s.walls.size(), back.walls.size(), differ);
  EXPECT_EQ(taken, s.size());
  EXPECT_TRUE(same_parcels(back.p, s.p));
  EXPECT_GT(split, 0);
  EXPECT_EQ(static_cast<long>(back.pairs.size()), static_cast<long>(s.pairs.size()) - split);
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(back.walls.size(), s.walls.size());
}

TEST(PortableState, GhostsAndTheirPairsAreLeftToTheirOwnRanks) {
  // Parcels 0..n_owned-1 owned, the rest ghosts: a pair with a ghost is recorded only
  // when the owned parcel has the lower id.
  Particles p;
  NeighborList nl;
  nl.skin = 0.1 * kD;
  const int64_t ids[] = {10, 30, 20, 40};  // chain along x; the last two become ghosts
  for (int i = 0; i < 4; ++i) test::add_distinct(p, ids[i], {i * kA, 0, 0}, kS);
  const geometry::Scene none;
  nl.build(p, none.at(0));
  test::set_histories(p, nl);
  ASSERT_EQ(p.id, std::vector<int64_t>(std::begin(ids), std::end(ids)));  // the sort kept the chain order
  const PortableState s = portable_state(p, nl, 2);
  // Pairs: (10,30) both owned -> kept; (30,20) split, lower id 20 is a ghost -> left out;
  // (20,40) two ghosts -> left out.
  ASSERT_EQ(s.size(), 2u);
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].id_a, 10);
  EXPECT_EQ(s.pairs[0].id_b, 30);
  const PortableState t = portable_state(p, nl, 3);  // 20 owned too: (20,30) kept, (20,40) split, 20 lower -> kept
  std::printf("[ ghosts ] owned 2 of 4: %zu pair records; owned 3 of 4: %zu\n", s.pairs.size(), t.pairs.size());
  EXPECT_EQ(t.pairs.size(), 3u);
}

TEST(PortableState, BadInputIsNamed) {
  Bed bed;
  const PortableState s = portable_state(bed.p, bed.nl);
  std::vector<PortableState> twice{s, s};
  EXPECT_NE(test::error_of([&] { merge(twice); }).find("is held twice"), std::string::npos);
  EXPECT_NE(test::error_of([&] { portable_state(bed.p, bed.nl, bed.p.size() + 1); }).find("owned parcels"),
            std::string::npos);
  io::ArchiveWriter w;
  save(w, s);
  std::string bytes = w.bytes();
  bytes.resize(bytes.size() / 2);
  io::ArchiveReader r(bytes, "half.bin");
  PortableState t;
  EXPECT_NE(test::error_of([&] { load(r, t); }), "(no error)");
}

}  // namespace
}  // namespace cgdem::parallel
