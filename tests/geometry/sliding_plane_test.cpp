// The warning for a shoe that slides on a plane that is not a plane of the air grid.
#include <gtest/gtest.h>

#include <cstdio>

#include "geometry/die_filling.hpp"

using namespace cgdem;

TEST(DieFillingGeometry, SlidingPlaneOffTheAirGridIsReported) {
  geometry::DieFillingParams p;
  p.table_top = 14e-3;  // no gap
  const std::string off = geometry::sliding_plane_warning(p, 0.0, 0.6e-3);
  std::printf("[ geometry ] table top 14 mm on 0.6 mm cells: %s\n", off.c_str());
  EXPECT_NE(off.find("z = 14 mm"), std::string::npos);
  EXPECT_NE(off.find("table_top = 13.8 or 14.4 mm"), std::string::npos);  // 23, 24 cells
  EXPECT_NE(off.find("1.8e-06"), std::string::npos);              // 0.1 m/s x 0.6 mm x 30 mm
  p.table_top = 14.4e-3;
  EXPECT_EQ(geometry::sliding_plane_warning(p, 0.0, 0.6e-3), "");
  EXPECT_NE(geometry::sliding_plane_warning(p, 0.1e-3, 0.6e-3), "");  // a shifted grid
  p.shoe_gap = 0.1e-3;
  const std::string gap = geometry::sliding_plane_warning(p, 0.0, 0.6e-3);
  std::printf("[ geometry ] 0.1 mm gap: %s\n", gap.c_str());
  EXPECT_NE(gap.find("thinner than a cell"), std::string::npos);
}
