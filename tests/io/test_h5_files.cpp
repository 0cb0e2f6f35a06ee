// The HDF5 files describe themselves and fail cleanly:
//   * every dataset of a particle state, a particle snapshot and an air snapshot has a
//     non-empty "units" and "description", and the files carry cgdem_revision, description,
//     time + time_units + step;
//   * compression: level 0 is contiguous, levels 1..9 chunk and shuffle + deflate the large
//     datasets, every level reads back bit for bit, and level 4 shrinks a smooth field;
//   * a truncated or garbage file gives one cgdem error naming the file, and HDF5 prints
//     nothing (its automatic error printing is off while src/io works, and restored after).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/h5_util.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "scratch.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

namespace {

ParticleTable bed(size_t n) {
  ParticleTable t;
  for (size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i);
    t.id.push_back(static_cast<int64_t>(3 * i + 1));
    t.species.push_back(0);
    t.x.push_back({1e-3 * std::fmod(s, 40), 1e-3 * std::fmod(s / 40, 40), 1e-4 * s / 1600});
    t.v.push_back({0.01 * std::sin(s), 0.0, -0.1});
    t.omega.push_back({0.0, 1.0, 0.0});
    t.d.push_back(3.75e-4);
  }
  return t;
}

struct DatasetInfo {
  std::string path, units, description;
  H5D_layout_t layout = H5D_CONTIGUOUS;
  int filters = 0;
};

// Every dataset of a file with its units, description, layout and number of filters.
std::vector<DatasetInfo> datasets(const std::string& file) {
  h5::Id f = h5::open_file(file);
  std::vector<DatasetInfo> out;
  auto visit = [](hid_t loc, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    if (info->type != H5O_TYPE_DATASET) return 0;
    auto& list = *static_cast<std::vector<DatasetInfo>*>(data);
    h5::Id ds(H5Dopen2(loc, name, H5P_DEFAULT), H5Dclose);
    const auto attrs = h5::read_string_attributes(ds, name);
    DatasetInfo d;
    d.path = name;
    if (attrs.count("units")) d.units = attrs.at("units");
    if (attrs.count("description")) d.description = attrs.at("description");
    h5::Id dcpl(H5Dget_create_plist(ds), H5Pclose);
    d.layout = H5Pget_layout(dcpl);
    d.filters = H5Pget_nfilters(dcpl);
    list.push_back(d);
    return 0;
  };
  H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, visit, &out, H5O_INFO_BASIC);
  return out;
}

size_t file_size(const std::string& p) { return static_cast<size_t>(std::filesystem::file_size(p)); }

// A smooth field on an nx x ny x nz grid, like a pressure or porosity field.
std::vector<double> smooth(int nx, int ny, int nz) {
  std::vector<double> f;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) f.push_back(20.0 * std::exp(-0.01 * ((i - 20) * (i - 20) + (j - 10) * (j - 10))) +
                                                1e-3 * k);
  return f;
}

}  // namespace

TEST(H5Files, EveryDatasetHasUnitsAndDescription) {
  const std::string dir = scratch_dir();
  const ParticleTable t = bed(500);
  const std::string state = dir + "/last_good.h5";
  write_particles_h5(state, t, {{"config", "[time]\nend = 1\n"}}, kDefaultCompression, Instant{0.125, 1250});
  SnapshotSeries particles(dir, "particles", {{"config", "x"}});
  const std::string snap =
      particles.write(7, 0.5, t, {{"speed", std::vector<double>(t.size(), 1.0)}}, {{"speed", {"m/s", "speed"}}});
  const int nx = 8, ny = 6, nz = 5;
  const std::vector<double> f = smooth(nx, ny, nz);
  GridSnapshotSeries air(dir, "air", {{"config", "x"}});
  const std::string grid =
      air.write(7, 0.5, nx, ny, nz, {0, 0, 0}, {1e-3, 1e-3, 1e-3}, {{"eps", f}, {"p", f}, {"alpha", f}}, {{"u", {f, f, f}}});

  int checked = 0, missing = 0;
  for (const std::string& file : {state, snap, grid}) {
    for (const DatasetInfo& d : datasets(file)) {
      ++checked;
      if (d.units.empty() || d.description.empty()) {
        ++missing;
        ADD_FAILURE() << file << ":/" << d.path << " has no units or description";
      }
    }
    const Attributes a = read_h5_attributes(file);
    EXPECT_FALSE(a.at("cgdem_revision").empty()) << file;
    EXPECT_FALSE(a.at("description").empty()) << file;
    EXPECT_FALSE(a.at("config").empty()) << file;
    EXPECT_EQ(a.at("time_units"), "s") << file;
    h5::Id h(h5::open_file(file));
    std::printf("  %s: time %g s, step %g, description \"%s\"\n", std::filesystem::path(file).filename().c_str(),
                h5::read_double_attribute(h, "time", file), h5::read_double_attribute(h, "step", file),
                a.at("description").c_str());
  }
  std::printf("[ info ] %d datasets in 3 files, %d without units or description (expected 0)\n", checked, missing);
  EXPECT_EQ(checked, 7 + 8 + 7);  // state 7; snapshot 7 + /fields/speed; grid 3 + cells 4
  // The units of a few, as documented.
  for (const DatasetInfo& d : datasets(grid)) {
    if (d.path == "cells/p") EXPECT_EQ(d.units, "Pa");
    if (d.path == "cells/u") EXPECT_EQ(d.units, "m/s");
    if (d.path == "cells/eps") EXPECT_EQ(d.units, "1");
  }
  for (const DatasetInfo& d : datasets(state)) {
    if (d.path == "particles/x") EXPECT_EQ(d.units, "m");
    if (d.path == "particles/omega") EXPECT_EQ(d.units, "rad/s");
  }
}

TEST(H5Files, CompressionLevelsReadBackExactly) {
  const std::string dir = scratch_dir();
  const ParticleTable t = bed(5000);
  size_t size0 = 0;
  for (int level : {0, 1, 4, 9}) {
    const std::string f = dir + "/level" + std::to_string(level) + ".h5";
    write_particles_h5(f, t, {}, level);
    const ParticleTable back = read_particles_h5(f);
    EXPECT_TRUE(back.x == t.x && back.v == t.v && back.omega == t.omega && back.d == t.d && back.id == t.id &&
                back.species == t.species)
        << "level " << level;
    int chunked = 0, filtered = 0, n = 0;
    for (const DatasetInfo& d : datasets(f)) {
      ++n;
      chunked += d.layout == H5D_CHUNKED;
      filtered += d.filters == 2;  // shuffle + deflate
    }
    if (level == 0) size0 = file_size(f);
    std::printf("[ info ] level %d: %zu bytes (%.3f of level 0), %d of %d datasets chunked, %d with shuffle+deflate\n",
                level, file_size(f), static_cast<double>(file_size(f)) / size0, chunked, n, filtered);
    EXPECT_EQ(chunked, level == 0 ? 0 : n);  // every particle array is above kMinCompressedBytes here
    EXPECT_EQ(filtered, level == 0 ? 0 : n);
  }
  // A smooth field (a grid of 40 x 30 x 20, full-precision doubles) shrinks at level 4 to
  // less than 3/4 (measured 0.58): the filter is really applied to the cell fields.
  GridSnapshotSeries plain(dir + "/g0", "air", {}, false, 0), packed(dir + "/g4", "air", {}, false, 4);
  const std::vector<double> f = smooth(40, 30, 20);
  const std::string a = plain.write(1, 0.0, 40, 30, 20, {0, 0, 0}, {1e-3, 1e-3, 1e-3}, {{"p", f}});
  const std::string b = packed.write(1, 0.0, 40, 30, 20, {0, 0, 0}, {1e-3, 1e-3, 1e-3}, {{"p", f}});
  const double ratio = static_cast<double>(file_size(b)) / file_size(a);
  std::printf("[ info ] smooth 40x30x20 field: %zu -> %zu bytes at level 4 (ratio %.3f, tolerance < 0.75)\n",
              file_size(a), file_size(b), ratio);
  EXPECT_LT(ratio, 0.75);
  for (const DatasetInfo& d : datasets(b))
    if (d.path == "grid/n") EXPECT_EQ(d.layout, H5D_CONTIGUOUS);  // 24 bytes: never filtered
}

TEST(H5Files, DamagedFilesGiveOneMessageAndNoHdf5Printing) {
  const std::string dir = scratch_dir();
  const std::string good = dir + "/good.h5";
  write_particles_h5(good, bed(2000), {{"config", std::string(3000, 'c')}});
  std::string bytes;
  {
    std::ifstream in(good, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_GT(bytes.size(), 4096u);
  const std::string truncated = dir + "/truncated.h5", garbage = dir + "/garbage.h5";
  spit(truncated, bytes.substr(0, bytes.size() / 2));
  spit(garbage, std::string(bytes.size(), 'x'));

  H5E_auto2_t before = nullptr;
  void* before_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &before, &before_data);
  for (const std::string& f : {truncated, garbage}) {
    testing::internal::CaptureStderr();
    std::string message;
    try {
      read_particles_h5(f);
    } catch (const Error& e) {
      message = e.what();
    }
    const std::string err = testing::internal::GetCapturedStderr();
    std::printf("  %s -> \"%s\"; %zu bytes on stderr (expected 0)\n", std::filesystem::path(f).filename().c_str(),
                message.c_str(), err.size());
    EXPECT_NE(message.find(f), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(err, "") << "HDF5 printed: " << err;
  }
  // The automatic error handler is what it was before (the silencing is scoped).
  H5E_auto2_t after = nullptr;
  void* after_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &after, &after_data);
  EXPECT_EQ(after, before);
  EXPECT_EQ(after_data, before_data);
  EXPECT_NE(before, nullptr);  // HDF5's default printer is installed in a test process
}
