// Block decomposition: owners, blocks and neighbour lists against hand-made expectations
// and against a brute-force definition (blocks that touch), and the choice of dims.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "../error_of.hpp"
#include "parallel/decomposition.hpp"

namespace cgdem::parallel {
namespace {

const geometry::Aabb kBox{{-1, 0, 2}, {3, 1.5, 2.5}};

std::string dims_text(const Dims& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

// Neighbours by definition: other ranks whose closed blocks share a point with this one,
// through the periodic images on periodic axes.
std::vector<int> touching(const Decomposition& d, int rank) {
  std::vector<int> out;
  const geometry::Aabb b = d.block(rank);
  for (int s = 0; s < d.ranks(); ++s) {
    if (s == rank) continue;
    const geometry::Aabb c = d.block(s);
    bool touch = true;
    for (int a = 0; a < 3; ++a) {
      const double L = d.box().hi[a] - d.box().lo[a];
      bool axis = false;
      for (int img = -1; img <= 1; ++img) {
        if (img != 0 && !d.periodic()[a]) continue;
        axis = axis || (c.lo[a] + img * L <= b.hi[a] && c.hi[a] + img * L >= b.lo[a]);
      }
      touch = touch && axis;
    }
    if (touch) out.push_back(s);
  }
  return out;
}

// Random points of the box go to the rank whose (half-open) block holds them, and the
// blocks tile the box.
void check_owners(const Decomposition& d) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  long wrong = 0;
  const long samples = 4000;
  for (long s = 0; s < samples; ++s) {
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = d.box().lo[a] + u(rng) * (d.box().hi[a] - d.box().lo[a]);
    const geometry::Aabb b = d.block(d.owner_of(x));
    if (!b.contains(x)) ++wrong;
  }
  double volume = 0;
  for (int r = 0; r < d.ranks(); ++r) {
    const geometry::Aabb b = d.block(r);
    volume += (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y) * (b.hi.z - b.lo.z);
  }
  const Vec3 e = d.box().hi - d.box().lo;
  const double vol_err = std::fabs(volume / (e.x * e.y * e.z) - 1);
  std::printf("[ owners ] %s: %ld of %ld random points outside their owner's block; blocks' volume error %.1e\n",
              dims_text(d.dims()).c_str(), wrong, samples, vol_err);
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(vol_err, 1e-14);
}

void check_neighbours(const Decomposition& d, const std::vector<std::vector<int>>& expected) {
  int differ = 0;
  for (int r = 0; r < d.ranks(); ++r) {
    const std::vector<int> got = d.neighbours(r);
    if (!expected.empty()) EXPECT_EQ(got, expected[r]) << "rank " << r << " of " << dims_text(d.dims());
    if (got != touching(d, r)) ++differ;
    EXPECT_EQ(got, touching(d, r)) << "rank " << r << " of " << dims_text(d.dims());
  }
  std::printf("[ neighbours ] %s%s: %d of %d ranks differ from the touching blocks\n", dims_text(d.dims()).c_str(),
              d.periodic()[0] || d.periodic()[1] || d.periodic()[2] ? " periodic" : "", differ, d.ranks());
}

TEST(Decomposition, OneBlockIsTheWholeBoxWithoutNeighbours) {
  Decomposition d(kBox, {1, 1, 1});
  EXPECT_EQ(d.ranks(), 1);
  EXPECT_EQ(d.owner_of({0, 1, 2.2}), 0);
  EXPECT_EQ(d.owner_of({-50, 70, 9}), 0);  // clamped
  EXPECT_EQ(d.block(0).lo, kBox.lo);
  EXPECT_EQ(d.block(0).hi, kBox.hi);
  check_neighbours(d, {{}});
  check_owners(d);
}

TEST(Decomposition, TwoBlocksAlongX) {
  Decomposition d(kBox, {2, 1, 1});
  EXPECT_EQ(d.block(0).hi.x, 1.0);
  EXPECT_EQ(d.block(1).lo.x, 1.0);
  EXPECT_EQ(d.owner_of({0.999, 1, 2.2}), 0);
  EXPECT_EQ(d.owner_of({1.0, 1, 2.2}), 1);  // a cut belongs to the upper block
  EXPECT_EQ(d.owner_of({3.0, 1.5, 2.5}), 1);  // the box's upper corner to the last block
  EXPECT_EQ(d.owner_of({-7, 0.2, 2.2}), 0);
  EXPECT_EQ(d.owner_of({9, 0.2, 2.2}), 1);
  check_neighbours(d, {{1}, {0}});
  check_owners(d);
}

TEST(Decomposition, TwoByTwoByOneEveryRankTouchesTheOthers) {
  Decomposition d(kBox, {2, 2, 1});
  EXPECT_EQ(d.owner_of({0.5, 0.5, 2.1}), 0);
  EXPECT_EQ(d.owner_of({1.5, 0.5, 2.1}), 1);
  EXPECT_EQ(d.owner_of({0.5, 1.0, 2.1}), 2);
  EXPECT_EQ(d.owner_of({1.5, 1.4, 2.1}), 3);
  EXPECT_EQ(d.owner_of({1.0, 0.75, 2.1}), 3);  // the shared corner line
  EXPECT_EQ(d.coords_of(3), (Dims{1, 1, 0}));
  check_neighbours(d, {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}});
  check_owners(d);
}

TEST(Decomposition, TwoByTwoByTwoEveryRankHasSevenNeighbours) {
  Decomposition d(kBox, {2, 2, 2});
  std::vector<std::vector<int>> all(8);
  for (int r = 0; r < 8; ++r)
    for (int s = 0; s < 8; ++s)
      if (s != r) all[r].push_back(s);
  EXPECT_EQ(d.owner_of({1.0, 0.75, 2.25}), 7);  // the corner of all eight
  check_neighbours(d, all);
  check_owners(d);
}

TEST(Decomposition, ThreeByTwoByOneMiddleAndCornerRanks) {
  Decomposition d(kBox, {3, 2, 1});
  // rank = i + 3 j: the middle column (i = 1) touches everyone, the sides three ranks.
  check_neighbours(d, {{1, 3, 4}, {0, 2, 3, 4, 5}, {1, 4, 5}, {0, 1, 4}, {0, 1, 2, 3, 5}, {1, 2, 4}});
  EXPECT_EQ(d.rank_of({2, 1, 0}), 5);
  for (int r = 0; r < 6; ++r) EXPECT_EQ(d.rank_of(d.coords_of(r)), r);
  check_owners(d);
}

TEST(Decomposition, ThreeByThreeByThreeCentreHasAllTwentySix) {
  Decomposition d(kBox, {3, 3, 3});
  EXPECT_EQ(d.neighbours(13).size(), 26u);
  check_neighbours(d, {});
  check_owners(d);
}

TEST(Decomposition, PeriodicAxesWrapAndListEachRankOnce) {
  // px = 2 periodic: rank 0 touches rank 1 on both sides, listed once.
  Decomposition two(kBox, {2, 1, 1}, {true, false, false});
  check_neighbours(two, {{1}, {0}});
  // px = 1 periodic: the image is the rank itself, not a neighbour.
  Decomposition one(kBox, {1, 2, 1}, {true, false, false});
  check_neighbours(one, {{1}, {0}});
  // px = 3 periodic: the ends touch each other.
  Decomposition three(kBox, {3, 1, 1}, {true, false, false});
  check_neighbours(three, {{1, 2}, {0, 2}, {0, 1}});
  Decomposition mixed(kBox, {3, 2, 2}, {true, false, true});
  check_neighbours(mixed, {});
  // Owners wrap instead of clamping on a periodic axis.
  EXPECT_EQ(three.owner_of({3.0 + 0.5, 1, 2.2}), 0);  // 3.5 wraps to -0.5
  EXPECT_EQ(three.owner_of({-1.0 - 0.5, 1, 2.2}), 2);
  EXPECT_TRUE(three.contains({100, 1, 2.2}));
  EXPECT_FALSE(three.contains({0, 2, 2.2}));
}

TEST(Decomposition, ContainsAndNaN) {
  Decomposition d(kBox, {2, 2, 1});
  EXPECT_TRUE(d.contains(kBox.lo));
  EXPECT_TRUE(d.contains(kBox.hi));
  EXPECT_FALSE(d.contains({3.0001, 1, 2.2}));
  EXPECT_FALSE(d.contains({NAN, 1, 2.2}));
  EXPECT_EQ(d.owner_of({NAN, NAN, NAN}), 0);
}

TEST(Decomposition, BadInputIsRejectedWithAMessage) {
  const std::string no_blocks = test::error_of([] { Decomposition(kBox, {2, 0, 1}); });
  const std::string empty = test::error_of([] { Decomposition({{0, 0, 0}, {1, 0, 1}}, {1, 1, 1}); });
  const std::string nan = test::error_of([] { Decomposition({{0, 0, 0}, {1, NAN, 1}}, {1, 1, 1}); });
  const std::string rank = test::error_of([] { Decomposition(kBox, {2, 1, 1}).block(2); });
  std::printf("[ errors ] %s\n[ errors ] %s\n[ errors ] %s\n[ errors ] %s\n", no_blocks.c_str(), empty.c_str(),
              nan.c_str(), rank.c_str());
  EXPECT_NE(no_blocks.find("0 blocks along y"), std::string::npos);
  EXPECT_NE(empty.find("along y is empty"), std::string::npos);
  EXPECT_NE(nan.find("along y is empty or not finite"), std::string::npos);
  EXPECT_NE(rank.find("rank 2 is not one of the 2 ranks"), std::string::npos);
}

// The least total cut area, sum_a (p_a - 1) A_a, by brute force over all factorisations.
double cut_area(const Dims& p, const Vec3& e) {
  return (p[0] - 1) * e.y * e.z + (p[1] - 1) * e.x * e.z + (p[2] - 1) * e.x * e.y;
}

TEST(ChooseDims, LeastCutAreaForTheBoxShape) {
  const Vec3 cube{1, 1, 1}, die{140, 70, 50}, flat{10, 10, 1};
  EXPECT_EQ(choose_dims(1, cube), (Dims{1, 1, 1}));
  EXPECT_EQ(choose_dims(2, cube), (Dims{2, 1, 1}));
  EXPECT_EQ(choose_dims(4, cube), (Dims{2, 2, 1}));
  EXPECT_EQ(choose_dims(8, cube), (Dims{2, 2, 2}));
  EXPECT_EQ(choose_dims(7, cube), (Dims{7, 1, 1}));
  EXPECT_EQ(choose_dims(4, flat), (Dims{2, 2, 1}));  // never across the thickness
  EXPECT_EQ(choose_dims(16, flat), (Dims{4, 4, 1}));
  EXPECT_EQ(choose_dims(2, die), (Dims{2, 1, 1}));
  EXPECT_EQ(choose_dims(64, die), (Dims{8, 4, 2}));
  long worse = 0;
  for (int n = 1; n <= 300; ++n)
    for (const Vec3& e : {cube, die, flat, Vec3{1, 3, 7}}) {
      const Dims p = choose_dims(n, e);
      ASSERT_EQ(p[0] * p[1] * p[2], n);
      for (int a = 1; a <= n; ++a)
        for (int b = 1; a * b <= n; ++b)
          if (n % (a * b) == 0 && cut_area({a, b, n / (a * b)}, e) < cut_area(p, e)) ++worse;
    }
  std::printf("[ dims ] die grid 140x70x50: 2 -> %s, 4 -> %s, 16 -> %s, 64 -> %s, 256 -> %s; "
              "%ld factorisations of 1..300 ranks cut less\n",
              dims_text(choose_dims(2, die)).c_str(), dims_text(choose_dims(4, die)).c_str(),
              dims_text(choose_dims(16, die)).c_str(), dims_text(choose_dims(64, die)).c_str(),
              dims_text(choose_dims(256, die)).c_str(), worse);
  EXPECT_EQ(worse, 0);
  const std::string bad_n = test::error_of([] { choose_dims(0, {1, 1, 1}); });
  const std::string bad_e = test::error_of([] { choose_dims(4, {1, 0, 1}); });
  std::printf("[ errors ] %s\n[ errors ] %s\n", bad_n.c_str(), bad_e.c_str());
  EXPECT_NE(bad_n.find("0 ranks"), std::string::npos);
  EXPECT_NE(bad_e.find("must be positive"), std::string::npos);
}

}  // namespace
}  // namespace cgdem::parallel
