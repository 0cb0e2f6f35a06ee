// The wall-primitive registry (geometry/primitives.hpp): the names the part reader and the
// help take, every row's reader on its own example (so a new row is checked without
// editing this file), the reader's messages.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "core/config.hpp"
#include "geometry/primitives.hpp"

namespace cgdem::geometry {
namespace {

ShapePtr read(const std::string& keys) {
  Config cfg = Config::from_string("[part]\n" + keys + "\n");
  ShapePtr s = read_primitive(cfg.root().section("part"));
  cfg.check_unused();
  return s;
}

TEST(WallPrimitives, NamesAndHelpComeFromTheTable) {
  const std::vector<std::string> names = wall_primitive_names();
  ASSERT_EQ(names.size(), wall_primitives().size());
  const std::string help = wall_primitive_help();
  for (const auto& n : names) EXPECT_NE(help.find(n), std::string::npos) << n;
  std::printf("[ primitives ] %zu:\n%s", names.size(), help.c_str());
}

// Every row: its example gives a solid whose gradient is a unit vector and agrees with the
// distance's differences (central, h = 1e-6) away from edges, whose bounds hold it, and
// whose inside_free form is its complement.
TEST(WallPrimitives, EveryRowReadsItsExample) {
  for (const PrimitiveRow& row : wall_primitives()) {
    const std::string keys = fmt::format("type = \"{}\"\n{}", row.name, row.example);
    const ShapePtr s = read(keys), free = read(keys + "\ninside_free = true");
    double worst_grad = 0, worst_unit = 0;
    int inside = 0, outside = 0, outside_bounds = 0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 x{-2.5 + 5.0 * std::fmod(0.618034 * k, 1.0), -2.5 + 5.0 * std::fmod(0.414214 * k, 1.0),
                   -2.5 + 6.0 * std::fmod(0.732051 * k, 1.0)};
      Vec3 g;
      const double d = s->distance_gradient(x, g);
      EXPECT_EQ(d, s->distance(x));
      EXPECT_EQ(free->distance(x), -d);
      (d < 0 ? inside : outside)++;
      if (d < 0 && s->bounds().distance(x) > 0) ++outside_bounds;
      worst_unit = std::max(worst_unit, std::fabs(norm(g) - 1));
      const double h = 1e-6;
      Vec3 fd;
      for (int a = 0; a < 3; ++a) {
        Vec3 xp = x, xm = x;
        xp[a] += h, xm[a] -= h;
        fd[a] = (s->distance(xp) - s->distance(xm)) / (2 * h);
      }
      if (std::fabs(norm(fd) - 1) < 1e-6) worst_grad = std::max(worst_grad, norm(fd - g));  // smooth there
    }
    std::printf("[ primitives ] %-10s %s: %d points inside, %d outside, %d inside but out of bounds; |grad| - 1 "
                "worst %.1e, gradient against differences worst %.1e (tol 1e-6)\n",
                std::string(row.name).c_str(), s->describe().c_str(), inside, outside, outside_bounds, worst_unit,
                worst_grad);
    EXPECT_GT(inside, 0) << row.name;
    EXPECT_GT(outside, 0) << row.name;
    EXPECT_EQ(outside_bounds, 0) << row.name;
    EXPECT_LT(worst_unit, 1e-12) << row.name;
    EXPECT_LT(worst_grad, 1e-6) << row.name;
  }
}

TEST(WallPrimitives, UnknownTypeNamesTheTable) {
  try {
    read("type = \"cube\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]");
    ADD_FAILURE() << "an unknown type was read";
  } catch (const ConfigError& e) {
    std::printf("[ primitives ] %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find(
                  fmt::format("expected one of {}, got \"cube\"", fmt::join(wall_primitive_names(), ", "))),
              std::string::npos);
  }
}

}  // namespace
}  // namespace cgdem::geometry
