// Neighbour lists against an all-pairs search: every pair (and periodic image) within
// r_i + r_j + skin is in the lists, once, under its lower index, with the partners of an
// owner in increasing order, and nothing else is. Two parcel sizes; an open box, a box
// periodic along x, and one periodic on every axis with only three cells per period (every
// row of cells there needs an image).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <set>
#include <tuple>

#include "dem_test_util.hpp"
#include "particles/neighbor_list.hpp"

namespace cgdem {
namespace {

using Entry = std::tuple<int, int, int>;  // owner, partner, image code

struct Box {
  Vec3 lo, hi;
  std::array<bool, 3> periodic;
};

// n parcels of two sizes (l = 3 and l = 2) at random places in the box (overlaps allowed:
// only the search is tested).
Particles random_parcels(int n, const Box& b, uint64_t seed) {
  const Species big = test::powder(3.0), small = test::powder(2.0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles p;
  for (int i = 0; i < n; ++i) {
    const Vec3 x{b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
                 b.lo.z + u(rng) * (b.hi.z - b.lo.z)};
    p.add(i, i % 3 == 0 ? 1 : 0, i % 3 == 0 ? small : big, x);
  }
  return p;
}

std::set<Entry> listed(const NeighborList& nl, long& out_of_order) {
  std::set<Entry> s;
  out_of_order = 0;
  for (int i = 0; i + 1 < static_cast<int>(nl.offset.size()); ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      s.insert({i, nl.partner[e], nl.image[e]});
      if (e > nl.offset[i] && !(nl.partner[e - 1] < nl.partner[e])) ++out_of_order;
    }
  return s;
}

// All pairs i < j and every image the periodic axes allow, with the lists' own test.
std::set<Entry> all_pairs(const Particles& p, const NeighborList& nl) {
  std::set<Entry> s;
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int code = 0; code < 27; ++code) {
        const int sx = code % 3 - 1, sy = code / 3 % 3 - 1, sz = code / 9 - 1;
        if ((sx && !nl.periodic.axis[0]) || (sy && !nl.periodic.axis[1]) || (sz && !nl.periodic.axis[2])) continue;
        const double reach = p.radius[i] + p.radius[j] + nl.skin;
        if (norm2(p.x[j] + nl.shift[code] - p.x[i]) < reach * reach) s.insert({i, j, code});
      }
  return s;
}

void check(const char* name, const Box& b, int n) {
  Particles p = random_parcels(n, b, 11);
  NeighborList nl;
  nl.skin = 0.1 * test::powder(3.0).diameter();
  nl.periodic.axis = b.periodic;
  nl.periodic.lo = b.lo, nl.periodic.hi = b.hi;
  const geometry::Scene none;
  nl.build(p, none.at(0));
  long out_of_order = 0;
  const std::set<Entry> got = listed(nl, out_of_order), want = all_pairs(p, nl);
  long missing = 0, extra = 0;
  for (const Entry& e : want) missing += !got.count(e);
  for (const Entry& e : got) extra += !want.count(e);
  const size_t entries = nl.partner.size();
  std::printf("[ lists ] %s: %d parcels, %zu entries, %zu pairs in reach; %ld missing, %ld extra, %zu repeated, "
              "%ld out of order\n",
              name, n, entries, want.size(), missing, extra, entries - got.size(), out_of_order);
  EXPECT_GT(want.size(), static_cast<size_t>(2 * n));  // dense enough to test something
  EXPECT_EQ(missing, 0);
  EXPECT_EQ(extra, 0);
  EXPECT_EQ(entries, got.size());
  EXPECT_EQ(out_of_order, 0);
}

TEST(NeighborLists, EqualAnAllPairsSearch) {
  const double d = test::powder(3.0).diameter();
  check("open box", {{0, 0, 0}, {14 * d, 9 * d, 7 * d}, {false, false, false}}, 1500);
  check("periodic along x", {{-2 * d, 0, 0}, {12 * d, 9 * d, 7 * d}, {true, false, false}}, 1500);
  // 3.4 diameters per period: three cells (each at least d + skin = 1.1 d wide) per axis
  check("periodic, three cells per axis", {{0, 0, 0}, {3.4 * d, 3.4 * d, 3.4 * d}, {true, true, true}}, 60);
}

}  // namespace
}  // namespace cgdem
