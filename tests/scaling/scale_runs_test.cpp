// The runs of a scaling study (scaling/scale_runs.hpp) resolve their cases through
// app::resolve_case_file, the resolver of `cgdem run`:
//  * the resolved text of read_study_info is exactly what resolve_case_file returns (and
//    so what the run writes to config.resolved.toml), for a vacuum case with a --set and
//    a die-filling case with air, given by absolute and by relative path;
//  * finished_run recognises a folder holding that configuration and a metrics.csv, and
//    rejects one of another configuration;
//  * bad input gives cgdem run's own message (an unknown key), and a flow case is rejected
//    with a clear message.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "app/run_command.hpp"
#include "core/error.hpp"
#include "scaling/scale_runs.hpp"
#include "tests/error_of.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem::scaling {
namespace {

namespace fs = std::filesystem;
using io::test::scratch_dir;
using io::test::spit;

const std::string kColumn = std::string(CGDEM_SOURCE_DIR) + "/validation/scaling_column_collapse/case.toml";
const std::string kDieFilling = std::string(CGDEM_SOURCE_DIR) + "/validation/die_filling/case_1_3.toml";

using cgdem::test::error_of;

TEST(ScaleRuns, StudyInfoIsResolvedAsCgdemRunResolvesIt) {
  const std::string report = scratch_dir();
  const auto plans = plan_runs({1, 2}, 0, report);
  ASSERT_EQ(plans.size(), 2u);
  write_derived_case(kColumn, plans[1]);
  const std::vector<std::string> sets = {"time.end=0.05"};
  const std::string out = fs::absolute(plans[1].dir).string();
  const StudyInfo info = read_study_info(plans[1].case_file, sets, out);
  const std::string run_resolved = app::resolve_case_file({plans[1].case_file, sets, out, ""});
  EXPECT_EQ(info.resolved, run_resolved);
  std::printf("l=2 derived case: %zu characters of resolved configuration, equal to cgdem run's: %s\n",
              info.resolved.size(), info.resolved == run_resolved ? "yes" : "no");
  // The study's view of the case, read back from the resolved text (case.toml: domain
  // [-1, 46] x [0, 8] x [-1, 40] mm, periodic in y, t in [-0.09, 0.05] s after the --set,
  // d_original 1 mm at l = 2, vacuum).
  EXPECT_DOUBLE_EQ(info.lo.x, -1e-3);
  EXPECT_DOUBLE_EQ(info.hi.x, 46e-3);
  EXPECT_DOUBLE_EQ(info.hi.z, 40e-3);
  EXPECT_EQ(info.periodic, (std::array<bool, 3>{false, true, false}));
  EXPECT_DOUBLE_EQ(info.t_start, -0.09);
  EXPECT_DOUBLE_EQ(info.t_end, 0.05);
  EXPECT_DOUBLE_EQ(info.d_original, 1e-3);
  EXPECT_DOUBLE_EQ(info.d_parcel_max, 2e-3);
  EXPECT_FALSE(info.air);
  EXPECT_FALSE(info.die_filling);

  // A finished run of this configuration is picked up; another configuration is not.
  spit(plans[1].dir + "/config.resolved.toml", "# cgdem test resolved configuration of case.toml\n" + run_resolved);
  spit(plans[1].dir + "/metrics.csv", "name,value\n");
  std::string why;
  EXPECT_TRUE(finished_run(plans[1], info, &why)) << why;
  const StudyInfo other = read_study_info(plans[1].case_file, {"time.end=0.06"}, out);
  EXPECT_FALSE(finished_run(plans[1], other, &why));
  EXPECT_NE(why.find("holds a run of a different configuration"), std::string::npos) << why;
}

TEST(ScaleRuns, RelativeCasePathAndAirCase) {
  // A path relative to the working directory, as `cgdem run` takes it.
  const std::string relative = fs::relative(kDieFilling, fs::current_path()).string();
  ASSERT_FALSE(fs::path(relative).is_absolute());
  const StudyInfo info = read_study_info(relative, {}, "");
  EXPECT_EQ(info.resolved, app::resolve_case_file({relative, {}, "", ""}));
  EXPECT_EQ(info.resolved, app::resolve_case_file({kDieFilling, {}, "", ""}));
  EXPECT_TRUE(info.air);
  EXPECT_TRUE(info.die_filling);
  EXPECT_NEAR(info.air_dx, 0.6e-3, 1e-12);  // 140 x 70 x 50 cells over 84 x 42 x 30 mm
  std::printf("die filling case by relative path '%s': air %d (dx %g m), die filling %d\n", relative.c_str(),
              info.air, info.air_dx, info.die_filling);
}

TEST(ScaleRuns, BadInputGivesCgdemRunsMessage) {
  const std::vector<std::string> sets = {"time.endd=0.05"};
  const std::string from_scale = error_of([&] { read_study_info(kColumn, sets, ""); });
  const std::string from_run = error_of([&] { app::resolve_case_file({kColumn, sets, "", ""}); });
  std::printf("scale: %s\nrun:   %s\n", from_scale.c_str(), from_run.c_str());
  EXPECT_NE(from_scale.find("endd"), std::string::npos);
  EXPECT_EQ(from_scale, from_run);
  const std::string missing = error_of([&] { read_study_info(kColumn + ".missing", {}, ""); });
  EXPECT_EQ(missing, error_of([&] { app::resolve_case_file({kColumn + ".missing", {}, "", ""}); }));
  const std::string flow = std::string(CGDEM_SOURCE_DIR) + "/tests/cli/converge/taylor_green.toml";
  const std::string not_particles = error_of([&] { read_study_info(flow, {}, ""); });
  EXPECT_NE(not_particles.find("a single-phase flow case ([flow]) has no particles to coarse-grain"), std::string::npos)
      << not_particles;
}

}  // namespace
}  // namespace cgdem::scaling
