// Neighbour lists against an all-pairs search: every pair (and periodic image) within
// r_i + r_j + skin is in the lists, once, under its lower index, with the partners of an
// owner in increasing order, and nothing else is. Two parcel sizes; an open box, boxes
// periodic along one axis (the slowest, the middle and the fastest in the cells' order), and
// one periodic on every axis with only three cells per period (every row of cells there
// needs an image).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <tuple>

#include "core/error.hpp"
#include "geometry/scene.hpp"
#include "geometry/shape.hpp"

#include "dem_test_util.hpp"
#include "io/archive.hpp"
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

// build() fills the storage of the lists before last (NeighborList::spare) instead of fresh
// arrays. Poisoned spare storage (NaN histories, partners -7, longer or shorter than needed)
// must leave no trace: each rebuild is compared bit for bit with the same build from empty
// storage. 1,500 parcels over a floor, every entry and wall candidate given a history of its
// own, moved between builds so that pairs come and go; then one parcel more (the old lists
// no longer fit: every history starts empty).
void poison(NeighborList& nl, size_t entries) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const contact::History bad{{nan, nan, nan}, {nan, nan, nan}, nan, nan};
  nl.spare.hist.assign(entries, bad);
  nl.spare.wall_hist.assign(entries / 8, bad);
  nl.spare.partner.assign(entries, -7);
  nl.spare.offset.assign(entries / 4, -7);
  nl.spare.wall_part.assign(entries / 8, -7);
  nl.spare.wall_offset.assign(entries / 4, -7);
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(NeighborLists, RebuildInSpareStorageEqualsAFreshBuild) {
  const double d = test::powder(3.0).diameter();
  const Box b{{0, 0, 0}, {14 * d, 9 * d, 7 * d}, {false, false, false}};
  Particles p = random_parcels(1500, b, 5);
  geometry::Scene scene;
  const int floor = scene.add_body("floor", geometry::Motion{});
  scene.add_part(floor, "floor", geometry::make_box({-1, -1, -1}, {1, 1, 0.5 * d}));
  NeighborList nl;
  nl.skin = 0.1 * d;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> G(0.0, 1.0);
  int compared = 0, differing = 0;
  size_t carried = 0, carried_before = 0;  // non-empty histories after the last build, and the one before
  for (int round = 0; round < 6; ++round) {
    if (round == 5) p.add(1500, 0, test::powder(3.0), {7 * d, 4 * d, 3 * d});
    // Spare storage poisoned: longer than the lists in even rounds, shorter in odd ones.
    if (round > 0) poison(nl, round % 2 ? nl.partner.size() / 2 : nl.partner.size() + 999);
    NeighborList fresh = nl;
    fresh.spare = NeighborList::Spare{};
    Particles q = p;
    nl.build(p, scene.at(0));
    fresh.build(q, scene.at(0));
    if (round > 0) {
      ++compared;
      differing += !same_bits(nl.offset, fresh.offset) + !same_bits(nl.partner, fresh.partner) +
                   !same_bits(nl.image, fresh.image) + !same_bits(nl.hist.records(), fresh.hist.records()) +
                   !same_bits(nl.wall_offset, fresh.wall_offset) + !same_bits(nl.wall_part, fresh.wall_part) +
                   !same_bits(nl.wall_hist, fresh.wall_hist) + !same_bits(p.x, q.x);
    }
    carried_before = carried, carried = 0;
    for (const contact::History& h : nl.hist.records()) carried += !h.empty();
    for (const contact::History& h : nl.wall_hist) carried += !h.empty();
    if (round == 5) break;
    // A history of its own for every entry and candidate (live, as the force pass leaves a
    // contact with a history); then every parcel moves.
    for (size_t e = 0; e < nl.hist.size(); ++e) {
      nl.hist.set(e, {{1.0 + e, 2.0, 3.0}, {4.0, 5.0, 6.0 + round}, 7.0, 8.0});
      nl.live[e] = 1;
    }
    for (size_t e = 0; e < nl.wall_hist.size(); ++e) nl.wall_hist[e] = {{-1.0 - e, 0, 0}, {}, 1.0, 0};
    for (Vec3& x : p.x) x += 0.05 * d * Vec3{G(rng), G(rng), G(rng)};
  }
  std::printf("[ lists ] %d rebuilds in poisoned spare storage against fresh storage: %d of %d arrays differ; "
              "%zu histories carried over by the fifth, %zu after the last (one parcel more)\n",
              compared, differing, 8 * compared, carried_before, carried);
  EXPECT_EQ(compared, 5);
  EXPECT_GT(carried_before, 1000u);  // the histories compared are not all empty
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(carried, 0u);  // the old lists did not fit: nothing carried, nothing stale
}

// derive() runs on lists read from a checkpoint and indexes by partner and by the entries'
// places in the reverse index: lists that do not hold together must be refused with an
// error, not followed out of range. 300 parcels, then one defect at a time.
TEST(NeighborLists, DeriveRefusesInconsistentLists) {
  const double d = test::powder(3.0).diameter();
  Particles p = random_parcels(300, {{0, 0, 0}, {8 * d, 6 * d, 5 * d}, {false, false, false}}, 9);
  NeighborList good;
  good.skin = 0.1 * d;
  good.build(p, geometry::Scene{}.at(0));
  ASSERT_GT(good.partner.size(), 100u);
  auto message = [&](auto&& spoil) {
    NeighborList nl = good;
    spoil(nl);
    try {
      nl.derive();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string partner_range = message([](NeighborList& nl) { nl.partner[7] = 300; });
  const std::string twice = message([](NeighborList& nl) { nl.rev_entry[1] = nl.rev_entry[0]; });
  const std::string offsets = message([](NeighborList& nl) { std::swap(nl.offset[10], nl.offset[200]); });
  const std::string shorter = message([](NeighborList& nl) { nl.partner.pop_back(), nl.hist.pop_back(); });
  const std::string intact = message([](NeighborList&) {});
  std::printf("[ lists ] partner out of range: %s\n[ lists ] an entry twice in the reverse index: %s\n"
              "[ lists ] offsets out of order: %s\n[ lists ] one entry fewer than the index: %s\n"
              "[ lists ] intact: %s\n",
              partner_range.c_str(), twice.c_str(), offsets.c_str(), shorter.c_str(), intact.c_str());
  EXPECT_NE(partner_range.find("out of range"), std::string::npos);
  EXPECT_NE(twice.find("does not list each entry once"), std::string::npos);
  EXPECT_NE(offsets.find("out of range"), std::string::npos);
  EXPECT_NE(shorter.find("out of range"), std::string::npos);
  EXPECT_EQ(intact, "(accepted)");
}

// The force pass skips the entries out of contact that are not live (compute_forces.cpp,
// select_active), which is right only while an entry that is not live holds an empty
// history (neighbor_list.hpp). The pass must keep that true: 343 parcels (l = 2) on a lattice with random velocities of up to 0.5 m/s fall
// onto a floor with gravity and collide for 3,000 steps. After every step, each entry
// that is not live must hold an empty history; the run must see contacts begin and end.
TEST(NeighborLists, AnEntryThatIsNotLiveHoldsNoHistory) {
  const Species sp = test::powder(2.0);
  const double d = sp.diameter(), dt = 1e-6;
  DemParams prm;
  prm.dt = dt;
  prm.domain = {{-1, -1, -1}, {1, 1, 1}};
  DemSolver dem({sp}, contact::ContactModel{}, prm, test::floor_scene());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int id = 0;
  for (int a = 0; a < 7; ++a)
    for (int b = 0; b < 7; ++b)
      for (int c = 0; c < 7; ++c)
        dem.particles().add(id++, 0, dem.species()[0], {1.02 * d * a, 1.02 * d * b, 0.6 * d + 1.02 * d * c},
                            0.29 * Vec3{U(rng), U(rng), U(rng)}, {});
  long violations = 0, ended = 0, live_max = 0, steps = 0;
  std::vector<uint8_t> had;  // per entry: a non-empty history after the step before
  long builds = -1;
  for (int k = 0; k < 3000; ++k) {
    dem.step();
    ++steps;
    const NeighborList& nl = dem.neighbor_list();
    long live = 0;
    const bool same_lists = nl.builds == builds;
    for (size_t e = 0; e < nl.hist.size(); ++e) {
      const bool empty = nl.hist.empty(e);
      violations += !nl.live[e] && !empty;
      live += nl.live[e];
      if (same_lists) ended += had[e] && empty;
    }
    had.resize(nl.hist.size());
    for (size_t e = 0; e < nl.hist.size(); ++e) had[e] = !nl.hist.empty(e);
    builds = nl.builds;
    live_max = std::max(live_max, live);
  }
  std::printf("[ lists ] %ld steps, %ld list builds: up to %ld live entries, %ld contacts ended between builds, "
              "%ld entries not live with a history (want 0)\n",
              steps, builds, live_max, ended, violations);
  EXPECT_GT(live_max, 100);
  EXPECT_GT(ended, 50);
  EXPECT_EQ(violations, 0);
}

// Lists loaded from a checkpoint are complete for the skin they were built with. Two l = 2
// parcels 50 um apart close head-on at 2 m/s (1 um per step each). A solver with the
// default skin (25 um) steps once, so its lists, which leave the pair out, go into a
// checkpoint. A solver with a skin of 100 um loads it: trusting those lists, it does not
// rebuild before some parcel has moved 50 um, so the parcels meet (after 25 steps) unseen and
// are found 25 um deep in each other: they fly apart at several times their impact speed.
// rebuild_lists_at_next_step() (what a restart does when [particles] changed) rebuilds at
// the first step: the collision then happens as in the first solver.
TEST(NeighborLists, ListsLoadedForAnotherSkinAreRebuilt) {
  const Species sp = test::powder(2.0);
  const double r = 0.5 * sp.diameter(), gap = 50e-6, dt = 1e-6;
  auto solver = [&](double skin) {
    DemParams prm = test::no_gravity(dt);
    prm.skin = skin;
    DemSolver dem({sp}, contact::ContactModel{}, prm, geometry::Scene{});
    dem.particles().add(0, 0, dem.species()[0], {-r - 0.5 * gap, 0, 0}, {1.0, 0, 0}, {});
    dem.particles().add(1, 0, dem.species()[0], {r + 0.5 * gap, 0, 0}, {-1.0, 0, 0}, {});
    return dem;
  };
  DemSolver first = solver(0.0);  // 0.1 d = 25 um
  first.step();
  io::ArchiveWriter w;
  first.save(w);
  auto velocity_after = [&](DemSolver& dem, bool rebuild) {
    io::ArchiveReader rd(w.bytes(), "checkpoint");
    dem.load(rd);
    if (rebuild) dem.rebuild_lists_at_next_step();
    for (int k = 0; k < 60; ++k) dem.step();
    const Particles& p = dem.particles();
    return p.v[p.id[0] == 0 ? 0 : 1].x;
  };
  for (int k = 0; k < 60; ++k) first.step();
  const Particles& p = first.particles();
  const double v_first = p.v[p.id[0] == 0 ? 0 : 1].x;
  DemSolver rebuilt = solver(100e-6), trusted = solver(100e-6);
  const double v_rebuilt = velocity_after(rebuilt, true), v_trusted = velocity_after(trusted, false);
  std::printf("[ lists ] parcel 0's velocity 61 steps after the start: %.6f m/s with its own lists, %.6f m/s "
              "loaded into a skin of 100 um and rebuilt, %.6f m/s loaded and trusted (the contact found late)\n",
              v_first, v_rebuilt, v_trusted);
  EXPECT_LT(v_first, 0.0);  // it bounced back
  EXPECT_LT(std::fabs(v_rebuilt - v_first), 1e-9);
  EXPECT_GT(std::fabs(v_trusted - v_first), 1.0);  // without the rebuild: what the guard prevents
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
