// Neighbour lists against an all-pairs search: every pair (and periodic image) within
// r_i + r_j + skin is in the lists, once, under its lower index, with the partners of an
// owner in increasing order, and nothing else is. Two parcel sizes; an open box, boxes
// periodic along one axis (the slowest, the middle and the fastest in the cells' order), and
// one periodic on every axis with only three cells per period (every row of cells there
// needs an image).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <set>
#include <tuple>

#include "geometry/scene.hpp"
#include "geometry/shape.hpp"

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
  // The cells are numbered with the axis of fewest cells fastest: a tall box (z slowest)
  // periodic along its middle axis, and a flat one whose fastest axis is periodic with three
  // cells (every row along it needs an image).
  check("tall, periodic along y", {{0, -2 * d, 0}, {6 * d, 5 * d, 14 * d}, {false, true, false}}, 1200);
  check("flat, periodic along z", {{0, 0, 0}, {14 * d, 9 * d, 3.4 * d}, {false, false, true}}, 900);
}

// The test of relative displacements (NeighborList::needs_rebuild with `relative`): while it
// says the lists are complete, every pair in contact is listed and every wall part a parcel
// touches is among its candidates. 400 parcels in a 12 x 8 x 6 d box: half rest, half ride
// with a wall body (a block sliding along x into the resting half, beside a static floor),
// and every parcel wanders a little on its own (a random walk). Checked at each of 2,000
// steps, over the builds the test asks for. The per-particle test alone (without
// `relative`) is counted beside it: it would build more often. The same check with the test
// fed twice the skin (lists built for one skin, trusted for two) finds contacts missing: it
// can fail.
struct RelativeRun {
  long builds = 0, checks = 0, contacts = 0, wall_contacts = 0;
  long missing_pairs = 0, missing_walls = 0;
};

RelativeRun run_lists(bool relative, double trusted_skin_factor) {
  const Species sp = test::powder(3.0);
  const double d = sp.diameter(), r = 0.5 * d, dt = 1e-6, u = 0.1;  // u: the block's speed [m/s]
  geometry::Scene scene;
  const int floor = scene.add_body("floor", geometry::Motion{});
  scene.add_part(floor, "floor", geometry::make_box({-1, -1, -1}, {1, 1, 0}));
  const int block = scene.add_body("block", geometry::Motion::constant({u, 0, 0}));
  scene.add_part(block, "block", geometry::make_box({-0.5 * d, 0, 0}, {0.5 * d, 8 * d, 2 * d}));
  Particles p;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> G(0.0, 1.0);
  const int n = 400;
  std::vector<double> riding(n);  // by id: 1 when the parcel moves with the block
  for (int i = 0; i < n; ++i) {
    riding[i] = i % 2;
    const double x0 = riding[i] ? U(rng) * 6 * d - 6.5 * d : 0.5 * d + U(rng) * 11 * d;
    p.add(i, 0, sp, {x0, U(rng) * 8 * d, r + U(rng) * 5 * d});
  }
  std::vector<Vec3> wander(n);  // by id: the random walk so far
  std::vector<Vec3> start(n);
  for (int i = 0; i < n; ++i) start[p.id[i]] = p.x[i];
  NeighborList nl;
  nl.skin = 0.1 * d;
  const double sigma = 0.002 * nl.skin;  // per step and axis
  RelativeRun out;
  auto place = [&](double t) {
    for (size_t i = 0; i < p.size(); ++i) {
      const int id = static_cast<int>(p.id[i]);
      p.x[i] = start[id] + wander[id] + Vec3{riding[id] * u * t, 0, 0};
    }
  };
  nl.build(p, scene.at(0));
  for (int step = 1; step <= 2000; ++step) {
    const double t = step * dt;
    for (int id = 0; id < n; ++id) wander[id] += sigma * Vec3{G(rng), G(rng), G(rng)};
    place(t);
    const geometry::Scene::Frame frame = scene.at(t);
    const MoveBounds moved = nl.moved_since_build(p);
    const double skin = nl.skin;
    nl.skin = trusted_skin_factor * skin;
    const bool rebuild = nl.needs_rebuild(moved, p.size(), frame, relative);
    nl.skin = skin;
    if (rebuild) {
      nl.build(p, frame);
      ++out.builds;
      continue;
    }
    ++out.checks;
    std::set<std::pair<int, int>> listed_pairs;
    for (int i = 0; i + 1 < static_cast<int>(nl.offset.size()); ++i)
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) listed_pairs.insert({i, nl.partner[e]});
    const int np = static_cast<int>(p.size());
    for (int i = 0; i < np; ++i) {
      for (int j = i + 1; j < np; ++j)
        if (norm(p.x[j] - p.x[i]) < p.radius[i] + p.radius[j]) {
          ++out.contacts;
          out.missing_pairs += !listed_pairs.count({i, j});
        }
      for (int q = 0; q < 2; ++q)
        if (frame.part_distance(q, p.x[i]) < p.radius[i]) {
          ++out.wall_contacts;
          bool found = false;
          for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) found = found || nl.wall_part[e] == q;
          out.missing_walls += !found;
        }
    }
  }
  return out;
}

TEST(NeighborLists, RelativeRebuildTestKeepsEveryContactListed) {
  const RelativeRun a = run_lists(true, 1.0), each = run_lists(false, 1.0), lax = run_lists(true, 2.0);
  std::printf("[ lists ] relative test: %ld builds in 2000 steps, %ld steps checked, %ld pair and %ld wall contacts "
              "seen, %ld and %ld missing\n",
              a.builds, a.checks, a.contacts, a.wall_contacts, a.missing_pairs, a.missing_walls);
  std::printf("[ lists ] per-particle test alone: %ld builds, %ld and %ld missing\n", each.builds, each.missing_pairs,
              each.missing_walls);
  std::printf("[ lists ] relative test trusted for twice the skin: %ld builds, %ld and %ld contacts missing (want > 0)\n",
              lax.builds, lax.missing_pairs, lax.missing_walls);
  EXPECT_GT(a.contacts, 100000);  // the check sees contacts come and go
  EXPECT_GT(a.wall_contacts, 1000);
  EXPECT_EQ(a.missing_pairs, 0);
  EXPECT_EQ(a.missing_walls, 0);
  EXPECT_EQ(each.missing_pairs + each.missing_walls, 0);
  EXPECT_LT(2 * a.builds, each.builds + 2);  // the relative test keeps the lists about twice as long
  EXPECT_GT(lax.missing_pairs + lax.missing_walls, 0);
}

}  // namespace
}  // namespace cgdem
