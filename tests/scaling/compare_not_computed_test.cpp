// `cgdem compare` of a run with air against one without: the vacuum run's metrics.csv has no
// pressure metrics (cgdem run leaves out what it cannot compute, app/run_metrics.hpp), and the
// comparison shows them as "not computed", with no NaN and no difference, not as an error.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "scaling/compare_report.hpp"
#include "scaling/compare_study.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem::scaling {
namespace {

using io::test::scratch_dir;
using io::test::slurp;
using io::test::spit;

std::string run(const std::string& root, const std::string& name, const std::string& metrics) {
  const std::string dir = root + "/" + name;
  std::filesystem::create_directories(dir);
  spit(dir + "/metrics.csv", "name,value\n" + metrics);
  spit(dir + "/diagnostics.csv", "t,mass_in_die\n0,0\n0.1,0.001\n0.2,0.002\n");
  return dir;
}

TEST(CompareNotComputed, AMetricMissingFromOneRunReadsNotComputed) {
  const std::string root = scratch_dir();
  const std::string air = run(root, "with_air", "fill_mass_kg,0.002\np_B_peak_Pa,15.5\np_B_peak_time_s,0.19\n");
  const std::string vac = run(root, "vacuum", "fill_mass_kg,0.003\n");
  const Comparison c = compare_runs({air, vac}, {}, {});
  const std::string out = root + "/report";
  write_compare_outputs(c, {out, "cgdem compare (test)", false});
  const std::string md = slurp(out + "/compare.md");
  const auto line = [&](const std::string& metric) {
    const size_t at = md.find("| " + metric + " |");
    return at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at);
  };
  std::printf("%s\n%s\n%s\n", line("p_B_peak_Pa").c_str(), line("p_B_peak_time_s").c_str(),
              line("fill_mass_kg").c_str());
  EXPECT_EQ(line("p_B_peak_Pa"), "| p_B_peak_Pa | Pa | 15.5 | not computed | — | — |");
  EXPECT_EQ(line("p_B_peak_time_s"), "| p_B_peak_time_s | s | 0.19 | not computed | — | — |");
  EXPECT_EQ(line("fill_mass_kg"), "| fill_mass_kg | kg | 0.002 | 0.003 | +0.001 | +50 % |");
  EXPECT_EQ(md.find("nan"), std::string::npos);
  EXPECT_NE(md.find("\"not computed\": the run did not write the metric"), std::string::npos);
  // The CSV keeps numbers only: an empty field, explained in its comment.
  const std::string csv = slurp(out + "/metrics_compare.csv");
  EXPECT_NE(csv.find("\np_B_peak_Pa,Pa,15.5,,,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("not computed (the run did not write the metric"), std::string::npos);
}

}  // namespace
}  // namespace cgdem::scaling
