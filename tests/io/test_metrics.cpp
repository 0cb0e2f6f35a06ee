#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "io/metrics.hpp"
#include "scratch.hpp"

using namespace cgdem;

TEST(Metrics, RoundTripIsExactAndKeepsOrder) {
  const std::string path = io::test::scratch_dir() + "/metrics.csv";
  const io::Metrics m{{"front_time_s", 0.0912345678901234}, {"fill_mass_kg", 1.0 / 3.0}, {"missing", NAN}};
  io::write_metrics(path, m);
  const io::Metrics r = io::read_metrics(path);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].first, "front_time_s");
  EXPECT_EQ(r[0].second, m[0].second);  // 17 significant digits: exact
  EXPECT_EQ(io::metric(r, "fill_mass_kg", path), 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(r[2].second));
}

TEST(Metrics, BadInputIsAClearError) {
  const std::string dir = io::test::scratch_dir();
  EXPECT_THROW(io::write_metrics(dir + "/a.csv", {{"bad name", 1.0}}), Error);
  std::ofstream(dir + "/b.csv") << "name,value\nx,abc\n";
  try {
    io::read_metrics(dir + "/b.csv");
    FAIL() << "a non-number was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(":2: 'abc' is not a number"), std::string::npos) << e.what();
  }
  const io::Metrics m{{"a", 1.0}};
  try {
    io::metric(m, "b", "run/metrics.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no metric 'b' (it has: a)"), std::string::npos) << e.what();
  }
}
