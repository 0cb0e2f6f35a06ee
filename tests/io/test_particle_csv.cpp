// particle_csv: exact round trip and one error message per kind of malformed input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "io/particle_csv.hpp"
#include "scratch.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A table with awkward doubles: random mantissas over many decades, -0, subnormals, extremes.
ParticleTable awkward_table(size_t n, bool with_v, bool with_omega) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-300, 300);
  auto r = [&] { return std::ldexp(mant(rng), expo(rng) / 10) * std::pow(10.0, expo(rng) % 20); };
  const double specials[] = {-0.0, 0.1, 1.0 / 3.0, M_PI, std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::max(), -std::numeric_limits<double>::min()};
  ParticleTable t;
  for (size_t i = 0; i < n; ++i) {
    double s = specials[i % 7];
    t.id.push_back(static_cast<int64_t>(i * 1000003) - 7);
    t.species.push_back(static_cast<int>(i % 3));
    t.x.push_back({r(), s, r()});
    t.d.push_back(std::fabs(r()) + 1e-300);
    if (with_v) t.v.push_back({r(), r(), s});
    if (with_omega) t.omega.push_back({s, r(), r()});
  }
  t.id[1] = std::numeric_limits<int64_t>::max();
  return t;
}

size_t count_bit_mismatches(const ParticleTable& a, const ParticleTable& b) {
  size_t bad = 0;
  auto v3 = [&](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    for (size_t i = 0; i < p.size(); ++i)
      for (int k = 0; k < 3; ++k) bad += !same_bits(p[i][k], q[i][k]);
  };
  v3(a.x, b.x), v3(a.v, b.v), v3(a.omega, b.omega);
  for (size_t i = 0; i < a.size(); ++i) bad += !same_bits(a.d[i], b.d[i]) + (a.id[i] != b.id[i]) + (a.species[i] != b.species[i]);
  return bad;
}

}  // namespace

TEST(ParticleCsv, RoundTripIsBitExact) {
  const std::string dir = scratch_dir();
  for (int variant = 0; variant < 3; ++variant) {
    ParticleTable t = awkward_table(500, variant >= 1, variant >= 2);
    const std::string f = dir + "/p" + std::to_string(variant) + ".csv";
    write_particles_csv(f, t);
    ParticleTable u = read_particles_csv(f);
    ASSERT_EQ(u.size(), t.size());
    ASSERT_EQ(u.v.size(), t.v.size());
    ASSERT_EQ(u.omega.size(), t.omega.size());
    size_t bad = count_bit_mismatches(t, u);
    std::printf("[ error ] variant %d: %zu of %zu values differ in any bit (tol 0)\n", variant, bad,
                t.size() * (5 + 3 * (variant >= 1) + 3 * (variant >= 2)));
    EXPECT_EQ(bad, 0u);
  }
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(ParticleCsv, ColumnsInAnyOrderWithDefaults) {
  ParticleTable t = parse_particles_csv(
      "# initial packing\n"
      "d , z,y,x\n"
      "\n"
      "1e-3, 3, 2, +1\r\n"
      "2e-3,6,5,4\n",
      "mem.csv");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.x[0], (Vec3{1, 2, 3}));
  EXPECT_EQ(t.x[1], (Vec3{4, 5, 6}));
  EXPECT_EQ(t.d[1], 2e-3);
  EXPECT_EQ(t.id, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(t.species, (std::vector<int>{0, 0}));
  EXPECT_TRUE(t.v.empty());
  EXPECT_TRUE(t.omega.empty());
  ParticleTable e = parse_particles_csv("x,y,z,d\n", "empty.csv");
  EXPECT_EQ(e.size(), 0u);
}

TEST(ParticleCsv, MalformedInputsNameFileAndLine) {
  struct Case {
    const char* text;
    int line;
    const char* needle;
  };
  const Case cases[] = {
      {"", 1, "missing header"},
      {"# only a comment\n", 2, "missing header"},
      {"x,y,d\n1,2,3\n", 1, "missing required column 'z'"},
      {"x,y,z\n", 1, "missing required column 'd'"},
      {"x,y,z,d,vx,vy\n", 1, "vx,vy,vz must be given all three"},
      {"x,y,z,d,wz\n", 1, "wx,wy,wz must be given all three"},
      {"x,y,z,d,x\n", 1, "'x' appears twice"},
      {"x,y,z,diameter\n", 1, "unknown column 'diameter'"},
      {"x,y,z,d\n1,2,3,0.1\n1,2,abc,0.1\n", 3, "column 'z': 'abc' is not a number"},
      {"x,y,z,d\n1,2,3,0.1\n1,2,3,\n", 3, "column 'd': '' is not a number"},
      {"x,y,z,d\n1.5e,2,3,0.1\n", 2, "'1.5e' is not a number"},
      {"x,y,z,d\n# c\nnan,2,3,0.1\n", 3, "must be finite"},
      {"x,y,z,d\n1,2,3,inf\n", 2, "must be finite"},
      {"x,y,z,d\n1,2,3,0\n", 2, "diameter must be > 0"},
      {"x,y,z,d\n1,2,3,-1e-3\n", 2, "diameter must be > 0"},
      {"x,y,z,d\n1,2,3,0.1,5\n", 2, "expected 4 fields (as in the header), found 5"},
      {"x,y,z,d\n\n1,2,3\n", 3, "expected 4 fields (as in the header), found 3"},
      {"x,y,z,d,id\n1,2,3,0.1,7.5\n", 2, "column 'id': '7.5' is not an integer"},
      {"id,x,y,z,d\n4,1,2,3,0.1\n5,1,2,3,0.1\n4,1,2,3,0.1\n", 4, "column 'id': 4 already used on line 2"},
      {"x,y,z,d,species\n1,2,3,0.1,-1\n", 2, "column 'species': must be >= 0"},
  };
  const std::string dir = scratch_dir();
  int k = 0;
  for (const Case& c : cases) {
    const std::string f = dir + "/bad" + std::to_string(k++) + ".csv";
    spit(f, c.text);
    const std::string where = f + ":" + std::to_string(c.line) + ": ";
    try {
      read_particles_csv(f);
      ADD_FAILURE() << "no error for input:\n" << c.text;
    } catch (const Error& e) {
      const std::string msg = e.what();
      std::printf("  %s\n", msg.c_str());
      EXPECT_EQ(msg.rfind(where, 0), 0u) << "message should start with '" << where << "': " << msg;
      EXPECT_NE(msg.find(c.needle), std::string::npos) << "message should mention '" << c.needle << "': " << msg;
    }
  }
  try {
    read_particles_csv(dir + "/missing.csv");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.csv"), std::string::npos) << e.what();
  }
}

TEST(ParticleTable, ValidateRejectsInconsistentSizes) {
  ParticleTable t = awkward_table(4, true, false);
  EXPECT_NO_THROW(t.validate());
  t.v.pop_back();
  EXPECT_THROW(t.validate(), Error);
  t.v.clear();
  EXPECT_NO_THROW(t.validate());
  t.id.push_back(9);
  try {
    t.validate("ctx");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ctx: 'id' has 5 entries but 'x' has 4"), std::string::npos) << e.what();
  }
  ParticleTable bad = awkward_table(3, false, false);
  EXPECT_THROW(write_particles_csv(scratch_dir() + "/never.csv", (bad.d.pop_back(), bad)), Error);
}
