// Migration buffers without MPI: every field of a parcel and every history it takes along
// come out of a buffer bit for bit, in the right frame, and land in the neighbour lists
// of the receiving side; two sets of lists in one process stand for two ranks.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <utility>

#include "../error_of.hpp"
#include "parallel/migration.hpp"
#include "parallel_test_util.hpp"

namespace cgdem::parallel {
namespace {

using test::same_bits;

const Species kS = test::powder_l3();
const double kD = kS.diameter(), kR = 0.5 * kD, kA = 0.98 * kD;  // lattice spacing: 2 % overlap

// nx x ny x nz parcels in contact, ids from id0, at x0 + (i, j, k) a (x0.z = 0.99 r:
// the bottom layer presses on the floor z = 0).
void add_lattice(Particles& p, int64_t id0, Vec3 x0, int nx, int ny, int nz) {
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) test::add_distinct(p, id0++, x0 + kA * Vec3{double(i), double(j), double(k)}, kS);
}

TEST(Migration, EveryFieldOfAParcelSurvivesTheBuffer) {
  Particles p;
  for (int i = 0; i < 6; ++i) test::add_distinct(p, 40 - 7 * i, {i * kD, 0, 0}, kS);
  int fields = 0;
  for_each_field(p, [&](const auto&) { ++fields; });
  const std::vector<int> dest = {-1, 1, 0, 1, -1, 0};
  NeighborList nl;  // never built: no histories
  const std::vector<Buffer> b = pack_leaving(p, nl, dest, 2);
  long differ = 0, moved = 0, distinct = 0;
  for (int d = 0; d < 2; ++d) {
    Particles q;
    NeighborList nq;
    const size_t n = unpack_arriving(b[d], q, nq);
    for (size_t i = 0, k = 0; i < dest.size(); ++i) {
      if (dest[i] != d) continue;
      ++moved;
      if (k >= n || test::bytes_of(q, k) != test::bytes_of(p, i)) ++differ;
      ++k;
    }
    EXPECT_EQ(q.size(), n);
  }
  // The values themselves must differ between parcels, or a mixed-up field would not show.
  for (size_t i = 1; i < p.size(); ++i) distinct += test::bytes_of(p, i) != test::bytes_of(p, 0);
  std::printf("[ fields ] %d fields of Particles, %zu bytes a parcel; %ld parcels through 2 buffers, %ld differ "
              "(bitwise), %ld of 5 parcels distinct from the first\n",
              fields, parcel_bytes(), moved, differ, distinct);
  // Every member of Particles is a std::vector: the bound fields must account for its size.
  EXPECT_EQ(fields * sizeof(std::vector<double>), sizeof(Particles));
  EXPECT_EQ(moved, 4);
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(distinct, 5);
  EXPECT_EQ(read_counts(b[0]).parcels, 2);
  EXPECT_EQ(read_counts(b[1]).pairs, 0);
}

TEST(Migration, PairHistoriesTravelInTheFrameOfTheLowerId) {
  // A chain along x: the owner of a pair is the lower local index after the cell sort,
  // the lower x here; ids fall along the first three parcels (the owner has the higher id)
  // and rise along the last three (the lower).
  Particles p;
  const int64_t ids[] = {100, 90, 80, 200, 300};
  for (int i = 0; i < 5; ++i) test::add_distinct(p, ids[i], {i * kA, 0, 0}, kS);
  NeighborList nl;
  nl.skin = 0.1 * kD;
  const geometry::Scene none;
  nl.build(p, none.at(0));
  // Owner-frame histories that differ from their flip, whatever the ids.
  for (size_t e = 0; e < nl.hist.size(); ++e) nl.hist.set(e, test::pair_history(static_cast<int64_t>(e), 1000));
  const std::vector<int> dest(p.size(), 0);
  const std::vector<Buffer> b = pack_leaving(p, nl, dest, 1);
  Particles q;
  NeighborList nq;
  unpack_arriving(b[0], q, nq);
  std::map<std::pair<int64_t, int64_t>, contact::History> carried;
  for (const CarriedPair& c : nq.incoming.pairs) carried[{c.id_a, c.id_b}] = c.h;
  int as_is = 0, flipped = 0, wrong = 0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int64_t a = p.id[i], b2 = p.id[nl.partner[e]];
      const auto it = carried.find({std::min(a, b2), std::max(a, b2)});
      const contact::History want = a < b2 ? nl.hist.get(e) : nl.hist.get(e).flipped();
      if (it == carried.end() || !same_bits(it->second, want)) ++wrong;
      (a < b2 ? as_is : flipped)++;
    }
  std::printf("[ pair frame ] %zu pairs carried: %d owned by the lower id (as is), %d by the higher (flipped), "
              "%d wrong\n",
              nq.incoming.pairs.size(), as_is, flipped, wrong);
  EXPECT_EQ(nq.incoming.pairs.size(), nl.hist.size());
  EXPECT_GT(as_is, 0);
  EXPECT_GT(flipped, 0);
  EXPECT_EQ(wrong, 0);
  for (const CarriedPair& c : nq.incoming.pairs) EXPECT_LT(c.id_a, c.id_b);
}

TEST(Migration, BuildAttachesACarriedPairInItsOwnersFrame) {
  const geometry::Scene floor = test::floor_scene();
  const contact::History h = test::pair_history(5, 9), hw = test::wall_history(5);
  for (bool high_id_first : {false, true}) {
    Particles p;
    // Same cell: the first added is the owner after the build's (stable) sort.
    test::add_distinct(p, high_id_first ? 9 : 5, {0, 0, 0.99 * kR}, kS);
    test::add_distinct(p, high_id_first ? 5 : 9, {kA, 0, 0.99 * kR}, kS);
    NeighborList nl;
    nl.skin = 0.1 * kD;
    nl.incoming.pairs = {{5, 9, h}, {5, 77, h}};       // 77: not here, dropped
    nl.incoming.walls = {{5, 0, hw}, {9, 3, hw}};      // part 3: no such contact, dropped
    nl.build(p, floor.at(0));
    ASSERT_EQ(nl.pair_entries(), 1u);
    const bool owner_is_5 = p.id[0] == 5;
    const contact::History want = owner_is_5 ? h : h.flipped();
    const int i5 = owner_is_5 ? 0 : 1, i9 = 1 - i5;
    ASSERT_EQ(nl.wall_offset[i5 + 1] - nl.wall_offset[i5], 1);
    const bool pair_ok = same_bits(nl.hist.get(0), want), wall_ok = same_bits(nl.wall_hist[nl.wall_offset[i5]], hw);
    const bool other_wall_empty = nl.wall_hist[nl.wall_offset[i9]].empty();
    std::printf("[ attach ] owner id %lld: pair history %s (xi.x %.3e, carried %.3e), wall %s; incoming left %zu\n",
                static_cast<long long>(p.id[0]), pair_ok ? "equal" : "DIFFERS", nl.hist.xi[0].x, h.xi.x,
                wall_ok ? "equal" : "DIFFERS", nl.incoming.pairs.size() + nl.incoming.walls.size());
    EXPECT_EQ(owner_is_5, !high_id_first);
    EXPECT_TRUE(pair_ok);
    EXPECT_EQ(nl.live[0], 1);
    EXPECT_TRUE(wall_ok);
    EXPECT_TRUE(other_wall_empty);
    EXPECT_TRUE(nl.incoming.empty());
  }
}

// Two ranks in one process. A holds a 4 x 2 x 2 block at x < 0; its half next to the cut
// x = 0 is mirrored to x > 0 (x -> -x, as a parcel crossing and seen in reverse cell
// order) and goes to B, which holds a block of its own. After both sides rebuild, every
// pair that stayed together has its history bit for bit, the pairs split by the cut have
// none, and every wall contact kept its history.
TEST(Migration, HistoriesFollowParcelsToAnotherSetOfLists) {
  const geometry::Scene floor = test::floor_scene();
  const auto frame = floor.at(0);
  Particles pa, pb;
  add_lattice(pa, 0, {-3.5 * kA, 0, 0.99 * kR}, 4, 2, 2);        // ids 0..15, x = -3.5a .. -0.5a
  add_lattice(pb, 100, {0.5 * kA - 0.5 * kD, 10 * kA, 0.99 * kR}, 3, 2, 2);  // ids 100..111, far in y
  NeighborList na, nb;
  na.skin = nb.skin = 0.1 * kD;
  na.build(pa, frame);
  nb.build(pb, frame);
  test::set_histories(pa, na);
  test::set_histories(pb, nb);
  // Before: who owns each pair (to count owner changes) and which pairs stay together.
  std::map<std::pair<int64_t, int64_t>, bool> owner_was_lower;
  auto moves = [](double x) { return x > -2 * kA; };  // the two columns next to the cut
  long together = 0, split = 0;
  for (const auto& [pp, nn] : {std::pair{&pa, &na}, std::pair{&pb, &nb}}) {
    const Particles& p = *pp;
    const NeighborList& nl = *nn;
    for (int i = 0; i < static_cast<int>(p.size()); ++i)
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int j = nl.partner[e];
        const int64_t a = std::min(p.id[i], p.id[j]), b = std::max(p.id[i], p.id[j]);
        owner_was_lower[{a, b}] = p.id[i] == a;
        const bool both_a = &p == &pa;
        (both_a && moves(p.x[i].x) != moves(p.x[j].x) ? split : together)++;
      }
  }
  long walls_before = static_cast<long>(na.wall_hist.size() + nb.wall_hist.size());

  std::vector<int> dest(pa.size(), -1);
  for (size_t i = 0; i < pa.size(); ++i)
    if (moves(pa.x[i].x)) {
      dest[i] = 0;
      pa.x[i].x = -pa.x[i].x;  // the drift
    }
  const std::vector<Buffer> to_b = pack_leaving(pa, na, dest, 1);
  const BufferCounts sent = read_counts(to_b[0]);
  apply_migration(pa, na, dest, {});
  apply_migration(pb, nb, std::vector<int>(pb.size(), -1), to_b);
  EXPECT_TRUE(na.needs_rebuild(pa, frame));
  na.build(pa, frame);
  nb.build(pb, frame);

  long equal = 0, wrong = 0, flips = 0, walls_equal = 0, walls_wrong = 0;
  for (const auto& [pp, nn] : {std::pair{&pa, &na}, std::pair{&pb, &nb}}) {
    const Particles& p = *pp;
    const NeighborList& nl = *nn;
    for (int i = 0; i < static_cast<int>(p.size()); ++i) {
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int64_t a = std::min(p.id[i], p.id[nl.partner[e]]), b = std::max(p.id[i], p.id[nl.partner[e]]);
        const auto before = owner_was_lower.find({a, b});
        const bool expected = before != owner_was_lower.end();
        const contact::History got = test::lower_id_frame(p, nl, i, e);
        const bool ok = expected ? same_bits(got, test::pair_history(a, b)) : got.empty();
        (ok ? equal : wrong)++;
        if (expected && before->second != (p.id[i] == a)) ++flips;
      }
      for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
        (same_bits(nl.wall_hist[e], test::wall_history(p.id[i])) ? walls_equal : walls_wrong)++;
    }
  }
  std::printf("[ two lists ] %lld parcels A -> B with %lld pair and %lld wall histories; pairs that stayed together "
              "%ld, split by the cut %ld; after the rebuilds: %ld pairs equal (bitwise), %ld wrong, owner changed for "
              "%ld; wall contacts %ld of %ld equal, %ld wrong\n",
              static_cast<long long>(sent.parcels), static_cast<long long>(sent.pairs),
              static_cast<long long>(sent.walls), together, split, equal, wrong, flips, walls_equal, walls_before,
              walls_wrong);
  EXPECT_EQ(pa.size() + pb.size(), 28u);
  EXPECT_EQ(sent.parcels, 8);
  EXPECT_GT(split, 0);
  EXPECT_EQ(equal, together);  // every pair that stayed together is listed again
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(flips, 0);
  EXPECT_EQ(walls_equal, walls_before);
  EXPECT_EQ(walls_wrong, 0);
}

TEST(Migration, BadInputIsRejectedWithAMessage) {
  Particles p;
  add_lattice(p, 0, {0, 0, 0.99 * kR}, 2, 1, 1);
  NeighborList nl;
  nl.skin = 0.1 * kD;
  const geometry::Scene none;
  nl.build(p, none.at(0));
  const std::vector<int> dest = {0, -1};
  const Buffer good = pack_leaving(p, nl, dest, 1)[0];
  Buffer short_buf(good.begin(), good.end() - 8), bad_tag = good;
  bad_tag[0] = std::byte{0};
  Particles q;
  NeighborList nq;
  Particles stale = p;
  test::add_distinct(stale, 9, {5 * kD, 0, 0}, kS);  // one more parcel than the lists hold
  Particles twins = p;
  twins.id[1] = twins.id[0];
  NeighborList twin_list;
  twin_list.incoming.pairs = {{0, 1, test::pair_history(0, 1)}};
  const std::string msgs[] = {
      test::error_of([&] { unpack_arriving(short_buf, q, nq); }),
      test::error_of([&] { unpack_arriving(bad_tag, q, nq); }),
      test::error_of([&] { pack_leaving(p, nl, std::vector<int>{0}, 1); }),
      test::error_of([&] { pack_leaving(p, nl, std::vector<int>{0, 3}, 2); }),
      test::error_of([&] { pack_leaving(stale, nl, std::vector<int>(3, -1), 1); }),
      test::error_of([&] { NeighborList l = nl; l.retain({1, 0}, 0); }),
      test::error_of([&] { twin_list.build(twins, none.at(0)); }),
  };
  const char* want[] = {"bytes after its header", "wrong tag", "1 destinations for 2 parcels",
                        "sent to destination 3, but there are 2", "the neighbour lists hold 2 particles",
                        "old particle 0, out of range", "is held twice"};
  for (int k = 0; k < 7; ++k) {
    std::printf("[ errors ] %s\n", msgs[k].c_str());
    EXPECT_NE(msgs[k].find(want[k]), std::string::npos) << msgs[k];
  }
  EXPECT_EQ(q.size(), 0u);  // a bad buffer adds nothing
}

}  // namespace
}  // namespace cgdem::parallel
