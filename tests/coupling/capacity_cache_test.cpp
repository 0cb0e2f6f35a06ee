// The kernel capacities kept from one call to the next where no moving part reaches
// (Exchange::capacity, porosity.cpp) must be bit for bit those a fresh evaluation gives, while
// a wall sweeps across the cells the cache has filled: one Exchange is kept over a sequence of
// wall positions, a new one (empty cache) evaluates every position from scratch.
//
// Scene: a static floor and a static wall with a cylinder post (a part that is not a box,
// so the capacity's signed distances go through the general path too), and a moving wall
// (a box, as the shoe's walls) that crosses the grid in steps of 0.7 cells, then jumps back.
// Every cell holds solid, so every node near a wall is evaluated. A frame repeated (the
// moving wall at rest) must take every capacity from the cache, the moving wall's too. The grid is periodic in y
// and the moving wall's y extent ends inside it: its periodic images must count as well.
// The test fails if the cache hands out a value the walls have changed. Checked: with the
// reach margin set to zero 23,416 values differ over the 33 positions; without the periodic
// images of the moving wall, 4,284.
#include <gtest/gtest.h>

#include <cstdio>

#include "coupling/exchange.hpp"
#include "fluid/ibm.hpp"
#include "geometry/scene.hpp"
#include "geometry/shape.hpp"

using namespace cgdem;

namespace {

struct Counts {
  long differ = 0, below_one = 0;
};

Counts compare(const fluid::Field& a, const fluid::Field& b) {
  Counts c;
  for (int k = 0; k < a.nk(); ++k)
    for (int j = 0; j < a.nj(); ++j)
      for (int i = 0; i < a.ni(); ++i) {
        c.differ += a(i, j, k) != b(i, j, k);
        c.below_one += b(i, j, k) < 1;
      }
  return c;
}

TEST(CapacityCache, KeptValuesEqualFreshEvaluationWhileAWallMoves) {
  const double dx = 0.6e-3;
  fluid::MacGrid g{32, 10, 14, dx, {0, 0, 0}};
  const std::vector<Species> species{{"powder", 125e-6, 3, 1500}};
  coupling::ExchangeParams ep;
  ep.bc = fluid::uniform_boundary(fluid::BcType::Wall);
  ep.bc[2] = ep.bc[3] = {fluid::BcType::Periodic, Vec3{}, 0};
  ep.wall_porosity = coupling::WallPorosity::Packing;

  geometry::Scene scene;
  const int fixed = scene.add_body("fixed", geometry::Motion{});
  scene.add_part(fixed, "floor", geometry::make_box({-1, -1, -1}, {1, 1, 1.9e-3}));
  scene.add_part(fixed, "end wall", geometry::make_box({16.3e-3, -1, -1}, {1, 1, 1}));
  scene.add_part(fixed, "post", geometry::make_cylinder({9.1e-3, 2.9e-3, 0}, {9.1e-3, 2.9e-3, 9e-3}, 0.8e-3));
  const double speed = 0.42;  // m/s: 0.7 cells per 1e-3 s
  const int shoe = scene.add_body("shoe", geometry::Motion::constant({speed, 0, 0}));
  scene.add_part(shoe, "shoe wall", geometry::make_box({-2.5e-3, 0.3e-3, 3.1e-3}, {-0.4e-3, 2.6e-3, 7.3e-3}));

  fluid::Field solid = fluid::make_cell_field(g);
  solid.fill(0.3 * dx * dx * dx);

  coupling::Exchange kept(g, species, ep);
  fluid::IbmFractions walls_kept;
  std::vector<double> times;
  for (int s = 0; s <= 30; ++s) times.push_back(1e-3 * s);
  times.push_back(5e-3);  // back to where it was: the cache filled meanwhile must not leak in
  times.push_back(5e-3);  // the same frame twice: nothing moved, so nothing is evaluated
  const double r = species[0].diameter() / 2;
  long total = 0, evaluated = 0, cached = 0;
  double previous = -1;
  for (double t : times) {
    const auto frame = scene.at(t);
    fluid::update_ibm(g, frame, 4, walls_kept);
    kept.set_walls(&walls_kept);
    kept.set_frame(&frame);
    fluid::Field cap_kept = fluid::make_cell_field(g);
    const auto nodes = kept.capacity(r, solid, cap_kept);

    coupling::Exchange fresh(g, species, ep);
    fluid::IbmFractions walls_fresh;
    fluid::update_ibm(g, frame, 4, walls_fresh);
    fresh.set_walls(&walls_fresh);
    fresh.set_frame(&frame);
    fluid::Field cap_fresh = fluid::make_cell_field(g);
    fresh.capacity(r, solid, cap_fresh);

    const Counts c = compare(cap_kept, cap_fresh);
    std::printf("[ capacity cache ] t = %.0f ms: %ld nodes with C < 1; kept exchange %ld from its cache, %ld evaluated; "
                "%ld differ from a fresh evaluation\n",
                1e3 * t, c.below_one, nodes[0], nodes[1], c.differ);
    cached += nodes[0];
    EXPECT_EQ(c.differ, 0) << "t = " << t;
    if (t == previous) {
      EXPECT_EQ(nodes[1], 0) << "the same frame again: every capacity should come from the cache";
      EXPECT_GT(nodes[0], 0);
    }
    previous = t;
    total += c.differ;
    evaluated += c.below_one;
  }
  EXPECT_GT(evaluated, 1000);  // the walls cut enough nodes for the comparison to mean something
  EXPECT_GT(cached, evaluated / 4);  // and the cache served a good part of them
  std::printf("[ capacity cache ] %zu positions: %ld values differ in all (tolerance: 0, bit for bit)\n", times.size(),
              total);
}

}  // namespace
