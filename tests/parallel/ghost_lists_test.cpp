// Neighbour lists with ghost parcels, and the migration records of split pairs, without
// MPI (issue 6, item 1; the MPI step is tests/parallel/mpi/distributed_dem_mpi_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <utility>

#include "../error_of.hpp"
#include "parallel/migration.hpp"
#include "parallel_test_util.hpp"

namespace cgdem::parallel {
namespace {

using test::same_bits;

const Species kS = test::powder_l3();
const double kD = kS.diameter(), kR = 0.5 * kD, kA = 0.98 * kD;

using IdPair = std::pair<int64_t, int64_t>;

// Pairs of the lists by id (lower id first).
std::set<IdPair> id_pairs(const Particles& p, const NeighborList& nl) {
  std::set<IdPair> s;
  for (int i = 0; i + 1 < static_cast<int>(nl.offset.size()); ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e)
      s.insert({std::min(p.id[i], p.id[nl.partner[e]]), std::max(p.id[i], p.id[nl.partner[e]])});
  return s;
}

// A 6 x 3 x 2 block of parcels in contact on a floor, x = 0 .. 5a; the last `ghosts` of
// them (those with x >= 3a, added last) stand for another rank's parcels.
TEST(GhostLists, GhostsStayInPlaceOwnNothingAndMeetTheOwnedParcels) {
  const geometry::Scene floor = test::floor_scene();
  const auto frame = floor.at(0);
  Particles all, p;
  int64_t id = 0;
  std::vector<int64_t> ghost_ids;
  for (int side = 0; side < 2; ++side)  // owned (x < 3a) first, then the ghosts
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          const Vec3 x = Vec3{(3 * side + (2 - i)) * kA, j * kA, 0.99 * kR + k * kA};  // reversed: build must sort
          const int64_t pid = 100 - id++;
          test::add_distinct(all, pid, x, kS);
          test::add_distinct(p, pid, x, kS);
          if (side == 1) ghost_ids.push_back(pid);
        }
  const size_t ng = ghost_ids.size(), no = p.size() - ng;
  NeighborList nl, na;
  nl.skin = na.skin = 0.1 * kD;
  nl.ghosts = ng;
  const Particles before = p;
  nl.build(p, frame);
  na.build(all, frame);

  // Ghosts keep their places and every field; the owned parcels were sorted (moved).
  long ghosts_moved = 0, owned_moved = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (i >= no) ghosts_moved += test::bytes_of(p, i) != test::bytes_of(before, i);
    else owned_moved += p.id[i] != before.id[i];
  }
  // No entry owned by a ghost, no ghost wall candidates, every partner above its owner.
  long ghost_entries = 0, ghost_walls = 0, order_wrong = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (i >= no) {
      ghost_entries += nl.offset[i + 1] - nl.offset[i];
      ghost_walls += nl.wall_offset[i + 1] - nl.wall_offset[i];
    }
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) order_wrong += nl.partner[e] <= static_cast<int>(i);
  }
  // The pairs: those of the lists without ghosts, less the ghost-ghost ones.
  const std::set<int64_t> is_ghost(ghost_ids.begin(), ghost_ids.end());
  std::set<IdPair> expected;
  for (const IdPair& q : id_pairs(all, na))
    if (!(is_ghost.count(q.first) && is_ghost.count(q.second))) expected.insert(q);
  const std::set<IdPair> got = id_pairs(p, nl);
  long split = 0;
  for (const IdPair& q : got) split += is_ghost.count(q.first) != is_ghost.count(q.second);
  long walls_owned = 0;
  for (size_t i = 0; i < no; ++i) walls_owned += nl.wall_offset[i + 1] - nl.wall_offset[i];
  std::printf("[ ghost lists ] %zu owned, %zu ghosts: %zu pairs (%zu expected), %ld of them with a ghost; ghosts "
              "moved %ld, owned parcels moved %ld; entries owned by ghosts %ld, ghost wall candidates %ld (owned %ld)\n",
              no, ng, got.size(), expected.size(), split, ghosts_moved, owned_moved, ghost_entries, ghost_walls,
              walls_owned);
  EXPECT_EQ(got, expected);
  EXPECT_GT(split, 0);
  EXPECT_EQ(ghosts_moved, 0);
  EXPECT_GT(owned_moved, 0);
  EXPECT_EQ(ghost_entries, 0);
  EXPECT_EQ(ghost_walls, 0);
  EXPECT_GT(walls_owned, 0);
  EXPECT_EQ(order_wrong, 0);

  // A history queued by id reaches the owned-ghost entry, in the owned parcel's frame.
  test::set_histories(p, nl);
  std::vector<CarriedPair> records;
  for (size_t i = 0; i < no; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e)
      if (static_cast<size_t>(nl.partner[e]) >= no) {
        const int64_t a = p.id[i], b = p.id[nl.partner[e]];
        records.push_back({std::min(a, b), std::max(a, b), test::pair_history(std::min(a, b), std::max(a, b))});
      }
  std::vector<int> keep(no);
  for (size_t i = 0; i < no; ++i) keep[i] = static_cast<int>(i);
  nl.retain(keep, ng);  // the particle set is "the same", rebuilt from scratch on the ghost side
  EXPECT_EQ(nl.ghosts, 0u);
  nl.ghosts = ng;
  for (size_t i = 0; i < no; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) EXPECT_LT(nl.partner[e], static_cast<int>(no));
  nl.incoming.pairs = records;
  nl.build(p, frame);
  long attached = 0, wrong = 0;
  for (size_t i = 0; i < no; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int64_t a = std::min(p.id[i], p.id[nl.partner[e]]), b = std::max(p.id[i], p.id[nl.partner[e]]);
      const bool ok = same_bits(test::lower_id_frame(p, nl, static_cast<int>(i), e), test::pair_history(a, b));
      if (static_cast<size_t>(nl.partner[e]) >= no) (ok ? attached : wrong)++;
      else wrong += !ok;  // the owned pairs kept theirs through retain()
    }
  std::printf("[ ghost lists ] %zu records for pairs with ghosts: %ld attached, %ld histories wrong\n", records.size(),
              attached, wrong);
  EXPECT_EQ(attached, static_cast<long>(records.size()));
  EXPECT_EQ(wrong, 0);
}

TEST(GhostLists, BadGhostCountsAreRejected) {
  Particles p;
  test::add_distinct(p, 1, {0, 0, kR}, kS);
  NeighborList nl;
  nl.skin = 0.1 * kD;
  nl.ghosts = 2;
  const geometry::Scene none;
  const std::string too_many = test::error_of([&] { nl.build(p, none.at(0)); });
  nl.ghosts = 1;
  nl.periodic.axis = {true, false, false};
  nl.periodic.lo = {-1, -1, -1};
  nl.periodic.hi = {1, 1, 1};
  const std::string periodic = test::error_of([&] { nl.build(p, none.at(0)); });
  std::printf("[ errors ] %s\n[ errors ] %s\n", too_many.c_str(), periodic.c_str());
  EXPECT_NE(too_many.find("2 ghosts among 1 particles"), std::string::npos);
  EXPECT_NE(periodic.find("periodic axes are not supported"), std::string::npos);
}

// A migration that splits a pair: the leaving side sends the history, the staying side
// keeps it by id; a record already queued that names a leaver goes with it.
TEST(GhostLists, AMigrationThatSplitsAPairKeepsItsHistoryOnBothSides) {
  const geometry::Scene floor = test::floor_scene();
  const auto frame = floor.at(0);
  Particles p;
  for (int i = 0; i < 4; ++i) test::add_distinct(p, 10 + i, {i * kA, 0, 0.99 * kR}, kS);  // a row in contact
  NeighborList nl;
  nl.skin = 0.1 * kD;
  nl.build(p, frame);
  test::set_histories(p, nl);
  const contact::History h_ghost = test::pair_history(13, 77);
  nl.incoming.pairs = {{13, 77, h_ghost}, {10, 88, test::pair_history(10, 88)}};  // 77, 88: ghosts of the last lists
  std::vector<int> dest(p.size(), -1);
  for (size_t i = 0; i < p.size(); ++i)
    if (p.id[i] >= 12) dest[i] = 0;  // 12 and 13 leave: the pair (11, 12) is split
  const std::vector<Buffer> out = pack_leaving(p, nl, dest, 1);
  Particles q;
  NeighborList nq;
  unpack_arriving(out[0], q, nq);
  apply_migration(p, nl, dest, {});
  auto has = [](const NeighborList& l, int64_t a, int64_t b, const contact::History& h) {
    return std::any_of(l.incoming.pairs.begin(), l.incoming.pairs.end(),
                       [&](const CarriedPair& c) { return c.id_a == a && c.id_b == b && same_bits(c.h, h); });
  };
  const contact::History h_split = test::pair_history(11, 12);
  const bool sent_split = has(nq, 11, 12, h_split), kept_split = has(nl, 11, 12, h_split);
  const bool sent_ghost = has(nq, 13, 77, h_ghost), not_sent = !has(nq, 10, 88, test::pair_history(10, 88));
  const bool sent_inner = has(nq, 12, 13, test::pair_history(12, 13));
  std::printf("[ split ] pair (11, 12): sent %d, kept %d; (12, 13) sent %d; queued (13, 77) sent %d, (10, 88) stayed %d\n",
              sent_split, kept_split, sent_inner, sent_ghost, not_sent);
  EXPECT_TRUE(sent_split);
  EXPECT_TRUE(kept_split);
  EXPECT_TRUE(sent_inner);
  EXPECT_TRUE(sent_ghost);
  EXPECT_TRUE(not_sent);
  EXPECT_FALSE(has(nl, 12, 13, test::pair_history(12, 13)));  // both left: nothing to keep here
}

}  // namespace
}  // namespace cgdem::parallel
