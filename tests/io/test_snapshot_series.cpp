// SnapshotSeries / GridSnapshotSeries: HDF5 snapshots read back exactly, the XDMF index is
// well-formed and consistent with the files it references, restart re-indexing.
#include <gtest/gtest.h>

#include <cstdlib>

#include "core/error.hpp"
#include "io/grid_snapshot_series.hpp"
#include "io/snapshot_series.hpp"
#include "xdmf_check.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

namespace {

ParticleTable cloud(size_t n, bool with_v) {
  ParticleTable t;
  for (size_t i = 0; i < n; ++i) {
    double s = static_cast<double>(i);
    t.id.push_back(static_cast<int64_t>(100 + i));
    t.species.push_back(static_cast<int>(i % 2));
    t.x.push_back({0.001 * s, 0.002 * s, 0.1 / (1 + s)});
    t.d.push_back(1e-4 * (1 + s));
    if (with_v) t.v.push_back({s, -s, 0.5});
  }
  t.omega = std::vector<Vec3>(n, Vec3{0, 0, 1});
  return t;
}

}  // namespace

TEST(SnapshotSeries, FilesAndIndexAreConsistent) {
  const std::string dir = scratch_dir() + "/out";
  const Attributes attrs = {{"config", "[dem]\ndt = 1e-6\n"}, {"git_revision", "abc123"}};
  SnapshotSeries series(dir, "particles", attrs);
  const double times[] = {0.0, 1e-3 / 3, 2e-3};
  for (int k = 0; k < 3; ++k) {
    ParticleTable t = cloud(5 + k, k < 2);
    ScalarFields extra = {{"coordination", std::vector<double>(t.size(), 3.0 + k)}, {"speed", t.d}};
    const FieldInfos info = {{"coordination", {"1", "contacts per parcel"}}, {"speed", {"m/s", "parcel speed"}}};
    const std::string p = series.write(10 * k, times[k], t, extra, info);
    EXPECT_EQ(p, dir + "/particles_0000" + std::to_string(k) + "0.h5");
    Attributes back;
    ParticleTable u = read_particles_h5(p, &back);
    EXPECT_TRUE(u.x == t.x && u.v == t.v && u.omega == t.omega && u.d == t.d && u.id == t.id);
    // The series' strings, the writer's own ones; numeric "time"/"step" are not strings.
    for (const auto& [key, value] : attrs) EXPECT_EQ(back[key], value) << key;
    EXPECT_EQ(back["time_units"], "s");
    EXPECT_FALSE(back["description"].empty());
    EXPECT_FALSE(back["cgdem_revision"].empty());
    EXPECT_EQ(back.size(), attrs.size() + 3);
  }
  EXPECT_EQ(count_temporaries(dir), 0);

  int items = 0;
  XmlNode root = check_xdmf(series.xdmf_path(), items);
  auto grids = root.all("Grid");
  ASSERT_EQ(grids.size(), 4u);  // collection + 3 snapshots
  for (int k = 0; k < 3; ++k) {
    const XmlNode& g = *grids[k + 1];
    EXPECT_EQ(std::strtod(g.all("Time")[0]->attr.at("Value").c_str(), nullptr), times[k]);
    EXPECT_EQ(g.all("Topology")[0]->attr.at("TopologyType"), "Polyvertex");
    EXPECT_EQ(g.all("Topology")[0]->attr.at("NumberOfElements"), std::to_string(5 + k));
    EXPECT_EQ(g.all("Geometry")[0]->attr.at("GeometryType"), "XYZ");
    const auto& topo = *g.all("Topology")[0];
    ASSERT_EQ(topo.all("DataItem").size(), 1u);  // explicit connectivity, one vertex per parcel
    EXPECT_EQ(topo.all("DataItem")[0]->attr.at("Dimensions"), std::to_string(5 + k) + " 1");
    std::vector<std::string> names;
    for (const XmlNode* a : g.all("Attribute")) names.push_back(a->attr.at("Name"));
    std::vector<std::string> want = {"velocity", "omega", "position", "diameter", "id", "species", "coordination",
                                     "speed"};
    if (k == 2) want.erase(want.begin());  // no velocity given at the last step
    EXPECT_EQ(names, want);
  }
  // Per snapshot: geometry, connectivity, 8 attributes (7 at the last step: no velocity).
  std::printf("[ info ] %d HDF DataItems checked against their datasets (expected %d)\n", items, 3 * 10 - 1);
  EXPECT_EQ(items, 3 * 10 - 1);

  // The extra fields are stored under /fields.
  h5::Id f = h5::open_file(series.snapshot_path(10));
  std::vector<hsize_t> dims;
  EXPECT_EQ(h5::read_double(f, "fields/coordination", dims, "s"), std::vector<double>(6, 4.0));
  EXPECT_EQ(h5::read_double_attribute(f, "time", "s"), times[1]);
}

TEST(SnapshotSeries, ResumeReindexesAndDropsLaterSteps) {
  const std::string dir = scratch_dir();
  {
    SnapshotSeries s(dir, "p", {});
    for (int k = 0; k < 4; ++k) s.write(100 * k, 0.1 * k, cloud(3, true), {{"f", {1, 2, 3}}}, {{"f", {"1", "f"}}});
  }
  SnapshotSeries again(dir, "p", {}, /*resume=*/true);
  EXPECT_EQ(again.steps(), (std::vector<int64_t>{0, 100, 200, 300}));
  again.write(150, 0.15, cloud(4, false));  // restart from a checkpoint at step 150
  EXPECT_EQ(again.steps(), (std::vector<int64_t>{0, 100, 150}));
  int items = 0;
  XmlNode root = check_xdmf(again.xdmf_path(), items);
  EXPECT_EQ(root.all("Grid").size(), 4u);
  EXPECT_EQ(slurp(again.xdmf_path()).find("p_000300.h5"), std::string::npos);
  // The re-indexed entry keeps its extra field.
  EXPECT_NE(slurp(again.xdmf_path()).find("p_000100.h5:/fields/f"), std::string::npos);
}

TEST(SnapshotSeries, RejectsBadInput) {
  const std::string dir = scratch_dir();
  SnapshotSeries s(dir, "p", {});
  const FieldInfos info = {{"f", {"1", "f"}}, {"id", {"1", "id"}}, {"a/b", {"1", "a/b"}}};
  EXPECT_THROW(s.write(0, 0, cloud(3, true), {{"f", {1, 2}}}, info), Error);        // wrong size
  EXPECT_THROW(s.write(0, 0, cloud(3, true), {{"id", {1, 2, 3}}}, info), Error);    // reserved
  EXPECT_THROW(s.write(0, 0, cloud(3, true), {{"a/b", {1, 2, 3}}}, info), Error);   // path separator
  EXPECT_THROW(s.write(0, 0, cloud(3, true), {{"g", {1, 2, 3}}}, info), Error);     // no units
  EXPECT_THROW(SnapshotSeries(dir, "p", {}, false, 10), Error);                     // level > 9
  EXPECT_THROW(SnapshotSeries(dir, "p", {{"description", "x"}}), Error);
  EXPECT_THROW(s.write(-1, 0, cloud(3, true)), Error);
  EXPECT_THROW(SnapshotSeries(dir, "a/b", {}), Error);
  EXPECT_THROW(SnapshotSeries(dir, "p", {{"time", "x"}}), Error);
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(GridSnapshotSeries, CellFieldsAndIndex) {
  const std::string dir = scratch_dir();
  const int nx = 4, ny = 3, nz = 2;
  const size_t nc = nx * ny * nz;
  CellScalars sc = {{"eps_f", std::vector<double>(nc)}, {"p", std::vector<double>(nc)}};
  CellVectors vec = {{"u_f", {std::vector<double>(nc), std::vector<double>(nc), std::vector<double>(nc)}}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        size_t c = i + nx * (j + ny * k);
        sc["p"][c] = static_cast<double>(c);
        sc["eps_f"][c] = 0.5;
        vec["u_f"][0][c] = i, vec["u_f"][1][c] = j, vec["u_f"][2][c] = k;
      }
  GridSnapshotSeries g(dir, "air", {{"git_revision", "abc"}});
  const FieldInfos info = {{"eps_f", {"1", "test"}}, {"u_f", {"m/s", "test"}}};
  const Vec3 origin{-1, 0.5, 2}, h{0.1, 0.2, 0.3};
  g.write(0, 0.0, nx, ny, nz, origin, h, sc, vec, info);
  g.write(5, 0.25, nx, ny, nz, origin, h, sc, vec, info);

  h5::Id f = h5::open_file(g.snapshot_path(5));
  std::vector<hsize_t> dims;
  std::vector<double> p = h5::read_double(f, "cells/p", dims, "g");
  EXPECT_EQ(dims, (std::vector<hsize_t>{nz, ny, nx}));
  std::vector<double> u = h5::read_double(f, "cells/u_f", dims, "g");
  EXPECT_EQ(dims, (std::vector<hsize_t>{nz, ny, nx, 3}));
  size_t bad = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        size_t c = i + nx * (j + ny * k);  // [k][j][i] row-major = c
        bad += p[c] != c;
        bad += u[3 * c] != i || u[3 * c + 1] != j || u[3 * c + 2] != k;
      }
  std::printf("[ error ] %zu misplaced cell values of %zu (tol 0)\n", bad, 2 * nc);
  EXPECT_EQ(bad, 0u);

  int items = 0;
  XmlNode root = check_xdmf(g.xdmf_path(), items);
  EXPECT_EQ(items, 2 * 3);
  const XmlNode& step = *root.all("Grid")[2];
  EXPECT_EQ(step.all("Topology")[0]->attr.at("TopologyType"), "3DCoRectMesh");
  EXPECT_EQ(step.all("Topology")[0]->attr.at("Dimensions"), "3 4 5");  // nodes, z y x
  auto geo = step.all("DataItem");
  EXPECT_EQ(geo[0]->text, "2 0.5 -1");              // origin z y x
  EXPECT_EQ(geo[1]->text, "0.29999999999999999 0.20000000000000001 0.10000000000000001");
  for (const XmlNode* a : step.all("Attribute")) EXPECT_EQ(a->attr.at("Center"), "Cell");

  GridSnapshotSeries again(dir, "air", {}, true);
  EXPECT_EQ(again.steps(), (std::vector<int64_t>{0, 5}));
  EXPECT_EQ(slurp(again.xdmf_path()), slurp(g.xdmf_path()));
  EXPECT_THROW(g.write(6, 0.3, nx, ny, nz, origin, h, {{"p", std::vector<double>(nc - 1)}}), Error);
  EXPECT_THROW(g.write(6, 0.3, 0, ny, nz, origin, h, {}), Error);
  EXPECT_THROW(g.write(6, 0.3, nx, ny, nz, origin, h, {{"u_f", sc["p"]}}, vec, info), Error);  // duplicate
  EXPECT_THROW(g.write(6, 0.3, nx, ny, nz, origin, h, {{"q", sc["p"]}}), Error);  // no units for "q"
  EXPECT_EQ(count_temporaries(dir), 0);
}
