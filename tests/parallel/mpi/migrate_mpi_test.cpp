// Migration over MPI (issue 6: "a parcel crossing a corner shared by several ranks keeps
// its contact history"). Run on 4 ranks (2 x 2 x 1 blocks) and on 1.
//
// Four clusters of 3 x 3 x 2 parcels in contact, one per block, hug the corner line
// x = y = 0 that all four blocks share; the bottom layer presses on a floor. Every pair
// and wall contact gets a history that follows from the ids. Then every position is
// mirrored through the corner line, (x, y) -> (-x, -y): each cluster lands whole in the
// diagonal block, across the corner, in reversed cell order (a cluster spans two cells of
// the list's grid along x and y, so the owners of some pairs change).
// After migrate() and a rebuild, every parcel must sit on the rank owning its position,
// with every field as before (bitwise; x mirrored), every pair and wall history as before
// (bitwise), and the totals unchanged. Checks are reduced over the ranks before they are
// asserted, so that every rank passes or fails together; rank 0 prints them.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "../../error_of.hpp"
#include "../mpi_util.hpp"
#include "../parallel_test_util.hpp"
#include "parallel/mpi/migrate.hpp"

namespace cgdem::parallel {
namespace {

using test::summed;
using test::world_rank;
using test::world_size;

const Species kS = test::powder_l3();
const double kD = kS.diameter(), kR = 0.5 * kD, kA = 0.98 * kD;

const geometry::Aabb kBox{{-6 * kA, -6 * kA, 0}, {6 * kA, 6 * kA, 4 * kA}};

Decomposition decomposition() {
  const int n = world_size();
  return Decomposition(kBox, n == 4 ? Dims{2, 2, 1} : choose_dims(n, kBox.hi - kBox.lo));
}

struct Seed {
  int64_t id;
  Vec3 x;
};

// Cluster q in the quadrant of signs (sx, sy) = (q & 1 ? + : -, q & 2 ? + : -): with 2 x 2 x 1
// blocks, cluster q starts on rank q.
std::vector<Seed> clusters() {
  std::vector<Seed> s;
  for (int q = 0; q < 4; ++q) {
    const double sx = q & 1 ? 1 : -1, sy = q & 2 ? 1 : -1;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          s.push_back({18 * q + 9 * k + 3 * j + i, {sx * (0.5 + i) * kA, sy * (0.5 + j) * kA, 0.99 * kR + k * kA}});
  }
  return s;
}

Vec3 mirrored(const Vec3& x) { return {-x.x, -x.y, x.z}; }

// (lower id, higher id) -> "the owner was the lower id", of every rank's lists.
std::map<std::pair<int64_t, int64_t>, bool> gathered_pairs(const Particles& p, const NeighborList& nl) {
  std::vector<int64_t> mine;
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int64_t a = std::min(p.id[i], p.id[nl.partner[e]]), b = std::max(p.id[i], p.id[nl.partner[e]]);
      mine.insert(mine.end(), {a, b, p.id[i] == a});
    }
  const int n = static_cast<int>(mine.size()), size = world_size();
  std::vector<int> count(size), start(size, 0);
  MPI_Allgather(&n, 1, MPI_INT, count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < size; ++r) start[r] = start[r - 1] + count[r - 1];
  std::vector<int64_t> all(start.back() + count.back());
  MPI_Allgatherv(mine.data(), n, MPI_INT64_T, all.data(), count.data(), start.data(), MPI_INT64_T, MPI_COMM_WORLD);
  std::map<std::pair<int64_t, int64_t>, bool> out;
  for (size_t k = 0; k < all.size(); k += 3) out[{all[k], all[k + 1]}] = all[k + 2] != 0;
  return out;
}

TEST(Migrate, ClustersCrossTheCornerToTheDiagonalRankWithTheirHistories) {
  const int rank = world_rank(), size = world_size();
  const Decomposition d = decomposition();
  const geometry::Scene floor = test::floor_scene();
  const auto frame = floor.at(0);
  const std::vector<Seed> seeds = clusters();

  // Masses that differ from parcel to parcel, so that the total depends on the order of
  // the sum and its check means something.
  auto add = [](Particles& q, int64_t id, const Vec3& x) {
    test::add_distinct(q, id, x, kS);
    q.inv_mass.back() /= 1 + 0.01 * static_cast<double>(id);
  };
  Particles p, reference;  // reference: every parcel as it must be after the move
  std::map<int64_t, size_t> ref_of;
  std::map<int64_t, int> start_rank;
  for (const Seed& s : seeds) {
    if (d.owner_of(s.x) == rank) add(p, s.id, s.x);
    add(reference, s.id, mirrored(s.x));
    ref_of[s.id] = reference.size() - 1;
    start_rank[s.id] = d.owner_of(s.x);
  }
  NeighborList nl;
  nl.skin = 0.1 * kD;
  nl.build(p, frame);
  test::set_histories(p, nl);
  const auto before = gathered_pairs(p, nl);
  const long walls_before = summed(static_cast<long>(nl.wall_hist.size()));
  const ParcelTotals t0 = global_totals(MPI_COMM_WORLD, p);

  for (Vec3& x : p.x) x = mirrored(x);  // the drift
  const MigrationCounts c = migrate(MPI_COMM_WORLD, d, p, nl);
  nl.build(p, frame);
  const ParcelTotals t1 = global_totals(MPI_COMM_WORLD, p);

  long misplaced = 0, fields_differ = 0, from_diagonal = 0, equal = 0, wrong = 0, flips = 0, walls_equal = 0,
       walls_wrong = 0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    misplaced += d.owner_of(p.x[i]) != rank;
    fields_differ += test::bytes_of(p, i) != test::bytes_of(reference, ref_of.at(p.id[i]));
    from_diagonal += start_rank.at(p.id[i]) == d.ranks() - 1 - rank;
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int64_t a = std::min(p.id[i], p.id[nl.partner[e]]), b = std::max(p.id[i], p.id[nl.partner[e]]);
      const auto was = before.find({a, b});
      const contact::History got = test::lower_id_frame(p, nl, i, e);
      const bool ok = was != before.end() ? test::same_bits(got, test::pair_history(a, b)) : got.empty();
      (ok ? equal : wrong)++;
      if (was != before.end() && was->second != (p.id[i] == a)) ++flips;
    }
    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
      (test::same_bits(nl.wall_hist[e], test::wall_history(p.id[i])) ? walls_equal : walls_wrong)++;
  }
  misplaced = summed(misplaced);
  fields_differ = summed(fields_differ);
  from_diagonal = summed(from_diagonal);
  equal = summed(equal);
  wrong = summed(wrong);
  flips = summed(flips);
  walls_equal = summed(walls_equal);
  walls_wrong = summed(walls_wrong);
  const long sent = summed(c.sent.parcels), received = summed(c.received.parcels);
  const long pairs_sent = summed(c.sent.pairs), walls_sent = summed(c.sent.walls);
  const double mass_err = std::fabs(t1.mass - t0.mass) / t0.mass;
  if (rank == 0) {
    std::printf("[ migrate ] %d rank(s), %d x %d x %d blocks: %lld parcels; sent %ld (received %ld) with %ld pair and "
                "%ld wall histories%s\n",
                size, d.dims()[0], d.dims()[1], d.dims()[2], static_cast<long long>(t0.count), sent, received,
                pairs_sent, walls_sent,
                size == 4 ? fmt::format("; {} now on the rank diagonal to their start", from_diagonal).c_str() : "");
    std::printf("[ migrate ] after rebuild: pair histories %ld equal (bitwise) of %zu listed before, %ld wrong, owner "
                "changed for %ld; wall histories %ld of %ld equal, %ld wrong; fields differing %ld; misplaced %ld\n",
                equal, before.size(), wrong, flips, walls_equal, walls_before, walls_wrong, fields_differ, misplaced);
    std::printf("[ migrate ] totals: count %lld -> %lld, id checksum %s, mass rel. error %.2e (tol 1e-14)\n",
                static_cast<long long>(t0.count), static_cast<long long>(t1.count),
                t0.id_checksum == t1.id_checksum ? "equal" : "DIFFERS", mass_err);
  }
  EXPECT_EQ(t0.count, static_cast<int64_t>(seeds.size()));
  EXPECT_EQ(t1.count, t0.count);
  EXPECT_EQ(t1.id_checksum, t0.id_checksum);
  EXPECT_LT(mass_err, 1e-14);
  EXPECT_EQ(misplaced, 0);
  EXPECT_EQ(fields_differ, 0);
  EXPECT_EQ(equal, static_cast<long>(before.size()));
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(walls_equal, walls_before);
  EXPECT_EQ(walls_wrong, 0);
  EXPECT_GT(walls_before, 0);
  EXPECT_GT(flips, 0);
  EXPECT_EQ(sent, received);
  if (size == 4) {  // every cluster crossed the corner
    EXPECT_EQ(sent, t0.count);
    EXPECT_EQ(from_diagonal, t0.count);
    EXPECT_EQ(pairs_sent, static_cast<long>(before.size()));
  } else if (size == 1) {
    EXPECT_EQ(sent, 0);
  }
}

// Every rank throws, the guilty one with the parcel, the others naming it: none is left
// waiting in a collective call.
void expect_raised_together(const std::string& message, const std::string& guilty_text) {
  const int rank = world_rank();
  const bool ok = message.find(rank == 0 ? guilty_text : "rank 0 found an error") != std::string::npos;
  const long ok_ranks = summed(ok);
  for (int r = 0; r < world_size(); ++r) {  // in rank order
    if (r == rank) std::printf("[ errors ] rank %d: %s\n", rank, message.c_str());
    std::fflush(stdout);
    MPI_Barrier(MPI_COMM_WORLD);
  }
  EXPECT_EQ(ok_ranks, world_size());
}

std::string error_of_migrate(const Decomposition& d, Particles& p) {
  NeighborList nl;
  return test::error_of([&] { migrate(MPI_COMM_WORLD, d, p, nl); });
}

TEST(Migrate, AParcelOutsideTheBoxStopsEveryRank) {
  const Decomposition d = decomposition();
  Particles p;
  if (world_rank() == 0) test::add_distinct(p, 5, {0.5 * kA, 0.5 * kA, 10 * kA}, kS);  // above the box
  expect_raised_together(error_of_migrate(d, p), "parcel id 5 at");
}

TEST(Migrate, AParcelBeyondTheNeighbouringBlocksStopsEveryRank) {
  const int size = world_size();
  if (size < 3) GTEST_SKIP() << "needs 3 ranks or more for a block that is not a neighbour";
  const Decomposition d(kBox, {size, 1, 1});
  Particles p;
  if (world_rank() == 0) test::add_distinct(p, 6, {kBox.hi.x - 0.1 * kA, 0, kR}, kS);  // in the last block
  expect_raised_together(error_of_migrate(d, p), "which is not a neighbour");
}

}  // namespace
}  // namespace cgdem::parallel
