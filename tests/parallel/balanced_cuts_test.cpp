// Uneven blocks (Decomposition from explicit cuts) and load-balancing cuts at the
// quantiles of the parcels (balanced_cuts): owners agree with blocks on the cuts
// themselves, shares are even, no block is narrower than one interaction range.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "../error_of.hpp"
#include "parallel/decomposition.hpp"

namespace cgdem::parallel {
namespace {

const geometry::Aabb kBox{{0, 0, 0}, {84e-3, 42e-3, 30e-3}};  // the die-filling domain

TEST(BalancedCuts, ExplicitCutsOwnTheirPointsLikeTheirBlocks) {
  const Decomposition d(kBox, Decomposition::Cuts{{{0, 10e-3, 11e-3, 84e-3}, {0, 42e-3}, {0, 5e-3, 30e-3}}});
  EXPECT_EQ(d.dims(), (Dims{3, 1, 2}));
  EXPECT_DOUBLE_EQ(d.narrowest_block(), 1e-3);
  long wrong = 0;
  // Points on every cut and just below it: the owner's block must hold the point, closed
  // on its lower faces and open on its upper ones (except the box's).
  for (double x : {0.0, 10e-3, std::nextafter(10e-3, 0.0), 11e-3, 50e-3, 84e-3})
    for (double z : {0.0, 5e-3, std::nextafter(5e-3, 0.0), 30e-3}) {
      const Vec3 p{x, 21e-3, z};
      const geometry::Aabb b = d.block(d.owner_of(p));
      for (int a = 0; a < 3; ++a) {
        const bool upper_box_face = b.hi[a] == kBox.hi[a];
        wrong += !(p[a] >= b.lo[a] && (p[a] < b.hi[a] || (upper_box_face && p[a] == b.hi[a])));
      }
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(d.owner_of({10.5e-3, 1e-3, 29e-3}), d.rank_of({1, 0, 1}));
}

TEST(BalancedCuts, BadCutsAreNamed) {
  using C = Decomposition::Cuts;
  EXPECT_NE(test::error_of([] { Decomposition(kBox, C{{{0, 50e-3, 40e-3, 84e-3}, {0, 42e-3}, {0, 30e-3}}}); })
                .find("must increase strictly"),
            std::string::npos);
  EXPECT_NE(test::error_of([] { Decomposition(kBox, C{{{1e-3, 84e-3}, {0, 42e-3}, {0, 30e-3}}}); })
                .find("must run from the box's"),
            std::string::npos);
  EXPECT_NE(test::error_of([] { balanced_cuts(kBox, {100, 1, 1}, {}, 1e-3); }).find("do not fit"), std::string::npos);
}

TEST(BalancedCuts, ParcelsOfTheShoeCavityAreSharedEvenly) {
  // 20,000 parcels in the shoe cavity (10 x 30 x 10 mm at x = 40..50 mm), as at the start
  // of the die filling: even blocks of the domain would give most ranks none.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(40e-3, 50e-3), uy(6e-3, 36e-3), uz(12e-3, 22e-3);
  std::vector<Vec3> pts(20000);
  for (auto& p : pts) p = {ux(rng), uy(rng), uz(rng)};
  const double range = 0.41e-3;  // 2 r + skin of the l = 3 parcels
  for (const Dims dims : {Dims{4, 1, 1}, Dims{1, 4, 1}, Dims{2, 2, 1}, Dims{2, 2, 2}}) {
    const Decomposition even(kBox, dims), bal(kBox, balanced_cuts(kBox, dims, pts, range));
    std::vector<long> n_even(even.ranks()), n_bal(bal.ranks());
    for (const auto& p : pts) ++n_even[even.owner_of(p)], ++n_bal[bal.owner_of(p)];
    const long most_even = *std::max_element(n_even.begin(), n_even.end());
    const long most = *std::max_element(n_bal.begin(), n_bal.end());
    const long least = *std::min_element(n_bal.begin(), n_bal.end());
    const double ideal = double(pts.size()) / bal.ranks();
    std::printf("[ balance ] %d x %d x %d: largest share %ld (even blocks: %ld), smallest %ld, ideal %.0f; narrowest "
                "block %.3g mm\n",
                dims[0], dims[1], dims[2], most, most_even, least, ideal, 1e3 * bal.narrowest_block());
    EXPECT_GE(bal.narrowest_block(), range);
    // One axis cut: exact quantiles (+-1). Two or three: independent coordinates, so
    // within a few percent of even (sampling noise of 20,000 points).
    const bool one_axis = (dims[0] > 1) + (dims[1] > 1) + (dims[2] > 1) == 1;
    const double tol = one_axis ? 1.0 : 0.05 * ideal;
    EXPECT_LE(most - ideal, tol);
    EXPECT_LE(ideal - least, tol);
    EXPECT_GT(most_even, 1.3 * ideal);  // the case for balancing
  }
}

TEST(BalancedCuts, NoBlockNarrowerThanTheRange) {
  // Every parcel on one plane: the quantile cuts would coincide; they are spread to the range.
  std::vector<Vec3> pts(1000, Vec3{42e-3, 21e-3, 15e-3});
  const auto cuts = balanced_cuts(kBox, {4, 1, 1}, pts, 1e-3);
  const Decomposition d(kBox, cuts);
  std::printf("[ narrow ] cuts along x at %.4g %.4g %.4g mm\n", 1e3 * cuts[0][1], 1e3 * cuts[0][2], 1e3 * cuts[0][3]);
  EXPECT_GE(d.narrowest_block(), 1e-3 * (1 - 1e-12));
}

}  // namespace
}  // namespace cgdem::parallel
