// particle_h5: bit-exact round trip of every array and of the string attributes
// (including a configuration text larger than HDF5's 64 KiB compact-attribute limit), and
// an interrupted write leaves the previous file intact.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/particle_h5.hpp"
#include "scratch.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

namespace {

ParticleTable sample(size_t n, bool with_v, bool with_omega) {
  ParticleTable t;
  for (size_t i = 0; i < n; ++i) {
    double s = 1.0 + 1e-3 * static_cast<double>(i);
    t.id.push_back(1000 + static_cast<int64_t>(i) * 7);
    t.species.push_back(static_cast<int>(i % 2));
    t.x.push_back({0.1 * s, -0.2 / s, 1.0 / 3.0 * s});
    t.d.push_back(1e-4 * s);
    if (with_v) t.v.push_back({s, -s, 1e-17 * s});
    if (with_omega) t.omega.push_back({-1e3 * s, 0.0, -0.0});
  }
  return t;
}

bool identical(const ParticleTable& a, const ParticleTable& b) {
  return a.id == b.id && a.species == b.species && a.x == b.x && a.v == b.v && a.omega == b.omega && a.d == b.d;
}

}  // namespace

TEST(ParticleH5, RoundTripWithAttributes) {
  const std::string dir = scratch_dir(), f = dir + "/particles.h5";
  std::string config;
  while (config.size() < 100000) config += "[dem]\nk_n = 1.0e4  # N/m\n";  // > 64 KiB
  const Attributes attrs = {{"config", config},
                            {"git_revision", "3f8631e-dirty"},
                            {"empty", ""},
                            {"unit note", "µm → m, \"quoted\""}};
  for (int variant = 0; variant < 3; ++variant) {
    ParticleTable t = sample(257, variant >= 1, variant >= 2);
    write_particles_h5(f, t, attrs);
    Attributes back;
    ParticleTable u = read_particles_h5(f, &back);
    EXPECT_TRUE(identical(t, u)) << "variant " << variant;
    // The given strings come back exactly; the writer adds its description and revision.
    size_t same = 0;
    for (const auto& [key, value] : attrs) same += back.count(key) && back.at(key) == value;
    EXPECT_EQ(same, attrs.size());
    EXPECT_EQ(back.size(), attrs.size() + 2);
    EXPECT_EQ(back.at("cgdem_revision"), kGitRevision);
    EXPECT_FALSE(back.at("description").empty());
    EXPECT_EQ(read_h5_attributes(f), back);
    std::printf("[ error ] variant %d: arrays identical = %d, %zu of %zu attributes identical (config %zu bytes)\n",
                variant, identical(t, u), same, attrs.size(), config.size());
  }
  // An empty table is a valid file too.
  write_particles_h5(f, ParticleTable{}, {});
  EXPECT_EQ(read_particles_h5(f).size(), 0u);
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(ParticleH5, FailureDuringWriteKeepsPreviousFile) {
  const std::string dir = scratch_dir(), f = dir + "/particles.h5";
  const ParticleTable good = sample(10, true, false);
  write_particles_h5(f, good, {{"git_revision", "abc"}});
  // An empty attribute name fails after the temporary file was created and partly written.
  EXPECT_THROW(write_particles_h5(f, sample(20, true, true), {{"", "bad"}, {"z", "late"}}), Error);
  EXPECT_EQ(count_temporaries(dir), 0);
  Attributes back;
  EXPECT_TRUE(identical(read_particles_h5(f, &back), good));
  EXPECT_EQ(back.at("git_revision"), "abc");
  // An inconsistent table is rejected before anything is written.
  ParticleTable bad = sample(5, true, false);
  bad.v.pop_back();
  EXPECT_THROW(write_particles_h5(f, bad), Error);
  EXPECT_TRUE(identical(read_particles_h5(f), good));
}

TEST(ParticleH5, ReadErrorsNameTheFile) {
  const std::string dir = scratch_dir();
  auto expect_error = [](const std::string& path, const std::string& needle) {
    try {
      read_particles_h5(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      std::printf("  %s\n", e.what());
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error(dir + "/absent.h5", "does not exist");
  spit(dir + "/text.h5", "x,y,z,d\n");
  expect_error(dir + "/text.h5", "not an HDF5 file");
}
