// The public snapshot reader (io/air_snapshot_reader.hpp) against the writers: an air
// snapshot written by io::GridSnapshotSeries and a particle snapshot written by
// io::SnapshotSeries are read back exactly (every value bit for bit, tolerance 0), and the
// scaling/fields.hpp helpers built on the reader (list_frames, read_cell_field) give the
// same values. Bad input (unknown field, vector read as a scalar, not a snapshot) names the
// file and the object.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "io/air_snapshot_reader.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/snapshot_series.hpp"
#include "scaling/fields.hpp"
#include "tests/error_of.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem {
namespace {

using io::test::scratch_dir;

using cgdem::test::error_of;

// Values that do not round-trip through a decimal print: the comparison must be exact.
std::vector<double> field(size_t n, double phase) {
  std::vector<double> v(n);
  for (size_t c = 0; c < n; ++c) v[c] = std::sin(0.37 * c + phase) / 3.0 + 1e-300 * (c % 2);
  return v;
}

// Largest |a - b| over the values, NaN-safe (a NaN counts as infinite).
double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return INFINITY;
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double x = std::fabs(a[i] - b[i]);
    d = std::isnan(x) ? INFINITY : std::max(d, x);
  }
  return d;
}

struct Written {
  int nx = 3, ny = 4, nz = 5;
  Vec3 origin{-1e-3, 2e-3 / 3, 0.5}, spacing{1e-3, 1.5e-3, 2e-3 / 3};
  io::CellScalars scalars;
  io::CellVectors vectors;
  std::string path;
  double time = 1e-3 / 3;
  int64_t step = 4242;
};

Written write_air(const std::string& dir) {
  Written w;
  const size_t n = static_cast<size_t>(w.nx) * w.ny * w.nz;
  w.scalars = {{"eps", field(n, 0.1)}, {"p", field(n, 2.0)}, {"alpha", field(n, -1.0)}};
  w.vectors = {{"u", {field(n, 3.0), field(n, 4.0), field(n, 5.0)}}};
  io::GridSnapshotSeries series(dir, "air", {{"config", "[air]\n"}});
  w.path = series.write(w.step, w.time, w.nx, w.ny, w.nz, w.origin, w.spacing, w.scalars, w.vectors);
  return w;
}

TEST(AirSnapshotReader, ReadsBackExactlyWhatTheWriterWrote) {
  const std::string dir = scratch_dir();
  const Written w = write_air(dir);
  const io::AirSnapshot s = io::read_air_snapshot(w.path);
  EXPECT_EQ(s.time, w.time);
  EXPECT_EQ(s.step, w.step);
  EXPECT_EQ(s.grid.n, (std::array<int64_t, 3>{w.nx, w.ny, w.nz}));
  EXPECT_TRUE(s.grid.origin == w.origin && s.grid.spacing == w.spacing);
  ASSERT_EQ(s.scalars.size(), w.scalars.size());
  ASSERT_EQ(s.vectors.size(), w.vectors.size());
  double worst = 0;
  size_t values = 0;
  for (const auto& [name, v] : w.scalars) {
    ASSERT_TRUE(s.scalars.count(name)) << name;
    worst = std::max(worst, max_abs_diff(s.scalars.at(name), v));
    EXPECT_TRUE(s.scalars.at(name) == v) << name;  // bit for bit
    values += v.size();
  }
  for (const auto& [name, v] : w.vectors)
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(s.vectors.count(name)) << name;
      worst = std::max(worst, max_abs_diff(s.vectors.at(name)[k], v[k]));
      EXPECT_TRUE(s.vectors.at(name)[k] == v[k]) << name << " component " << k;
      values += v[k].size();
    }
  std::printf("air snapshot: %zu values read back, max |read - written| = %g (tolerance: 0, exact)\n", values, worst);
  EXPECT_EQ(worst, 0.0);

  const io::AirGrid g = io::read_air_grid(w.path);
  EXPECT_EQ(g.cells(), static_cast<size_t>(w.nx * w.ny * w.nz));
  EXPECT_EQ(io::air_field_names(w.path), (std::vector<std::string>{"alpha", "eps", "p", "u"}));
  const io::AirSnapshot only_p = io::read_air_snapshot(w.path, {"p"});
  EXPECT_EQ(only_p.scalars.size(), 1u);
  EXPECT_TRUE(only_p.vectors.empty());
  EXPECT_TRUE(only_p.scalars.at("p") == w.scalars.at("p"));
}

TEST(AirSnapshotReader, ParticleSnapshotTimeAndTable) {
  const std::string dir = scratch_dir();
  io::ParticleTable t;
  for (int i = 0; i < 7; ++i) {
    t.id.push_back(i);
    t.species.push_back(0);
    t.x.push_back({i / 3.0, 1e-3 * i, 0.1});
    t.d.push_back(1e-3 / 7 * (i + 1));
  }
  io::SnapshotSeries series(dir, "particles", {});
  const std::string p0 = series.write(10, 1.0 / 3, t);
  const std::string p1 = series.write(20, 2.0 / 3, t);
  EXPECT_EQ(io::read_snapshot_time(p0), 1.0 / 3);
  EXPECT_EQ(io::read_snapshot_time(p1), 2.0 / 3);
  const auto frames = scaling::list_frames(dir, "particles");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].t, 1.0 / 3);
  EXPECT_EQ(frames[1].t, 2.0 / 3);
  EXPECT_EQ(frames[1].file, p1);
  const io::ParticleTable back = io::read_particles_h5(frames[0].file);
  EXPECT_TRUE(back.x == t.x && back.d == t.d && back.id == t.id);
  std::printf("particle snapshot: time read back %.17g (written %.17g), %zu particles exact\n", frames[0].t, 1.0 / 3,
              back.size());
}

TEST(AirSnapshotReader, FieldsHelpersUseTheReader) {
  const std::string dir = scratch_dir();
  const Written w = write_air(dir);
  scaling::Grid g;
  const std::vector<double> eps = scaling::read_cell_field(w.path, "eps", &g);
  EXPECT_TRUE(eps == w.scalars.at("eps"));
  EXPECT_EQ(g.nx, w.nx);
  EXPECT_EQ(g.ny, w.ny);
  EXPECT_EQ(g.nz, w.nz);
  EXPECT_EQ(g.dx, w.spacing.x);
  EXPECT_TRUE(g.origin == w.origin);
  const auto frames = scaling::list_frames(dir, "air");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].t, w.time);
}

TEST(AirSnapshotReader, BadInputNamesFileAndObject) {
  const std::string dir = scratch_dir();
  const Written w = write_air(dir);
  const std::string unknown = error_of([&] { io::read_air_snapshot(w.path, {"pressure"}); });
  std::printf("%s\n", unknown.c_str());
  EXPECT_NE(unknown.find(w.path + "': no cell field 'pressure' (it has alpha, eps, p, u)"), std::string::npos);
  const std::string vector = error_of([&] { scaling::read_cell_field(w.path, "u", nullptr); });
  EXPECT_NE(vector.find("cell field 'u' is a vector, a scalar is needed"), std::string::npos) << vector;
  const std::string missing = error_of([&] { io::read_air_snapshot(dir + "/air_999999.h5"); });
  EXPECT_NE(missing.find("air_999999.h5' does not exist"), std::string::npos) << missing;
  io::ParticleTable t;
  t.id = {1};
  t.species = {0};
  t.x = {{0, 0, 0}};
  t.d = {1e-3};
  io::SnapshotSeries particles(dir, "particles", {});
  const std::string p = particles.write(1, 0.5, t);
  const std::string not_air = error_of([&] { io::read_air_snapshot(p); });
  EXPECT_NE(not_air.find("no group '/grid' (not an air snapshot?)"), std::string::npos) << not_air;
  io::test::spit(dir + "/air_000002.h5", "not hdf5");
  const std::string garbage = error_of([&] { io::read_snapshot_time(dir + "/air_000002.h5"); });
  EXPECT_NE(garbage.find("not an HDF5 file"), std::string::npos) << garbage;
}

}  // namespace
}  // namespace cgdem
