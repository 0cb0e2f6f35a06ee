// `cgdem compare` (scaling/compare_study.hpp, compare_report.hpp) on synthetic run folders
// with known curves: the metric differences, the sampled curves and their normalised L2
// distances read back from the CSV files against their closed forms, NaN metrics and NaN
// curves reported as missing, columns beyond the usual ones carried through, the resolved
// configuration's differing keys, restarted rows, and every bad input named.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "scaling/compare_report.hpp"
#include "scaling/compare_study.hpp"
#include "scaling/csv_table.hpp"
#include "tests/error_of.hpp"
#include "tests/io/scratch.hpp"

using namespace cgdem::scaling;
using cgdem::io::test::scratch_dir;
using cgdem::io::test::slurp;
using cgdem::io::test::spit;
using cgdem::test::error_of;

namespace {

constexpr double kTol = 1e-12;

// diagnostics.csv with rows t = i * 1e-3 for i in [i0, i1] and one column per entry of `cols`
// (name -> y(t)); "nan" where y returns NaN.
void write_diagnostics(const std::string& dir, int i0, int i1,
                       const std::vector<std::pair<std::string, std::function<double(double)>>>& cols) {
  std::string s = "# cgdem def456, case synthetic.toml\nt";
  for (const auto& [n, f] : cols) s += "," + n;
  s += '\n';
  for (int i = i0; i <= i1; ++i) {
    const std::string text = fmt::format("{}e-3", i);
    const double t = std::stod(text);
    s += text;
    for (const auto& [n, f] : cols) {
      const double y = f(t);
      s += std::isfinite(y) ? fmt::format(",{:.17g}", y) : ",nan";
    }
    s += '\n';
  }
  spit(dir + "/diagnostics.csv", s);
}

std::string make_run(const std::string& root, const std::string& name, const std::string& metrics) {
  const std::string dir = root + "/" + name;
  std::filesystem::create_directories(dir);
  spit(dir + "/metrics.csv", "name,value\n" + metrics);
  return dir;
}

// Rows of a CSV file written by compare_report by their first field ('#' lines skipped);
// several rows with the same first field are keyed first,third (curves_distance.csv: curve,run).
std::map<std::string, std::vector<std::string>> rows(const std::string& path, bool key_with_third = false) {
  std::map<std::string, std::vector<std::string>> out;
  std::istringstream in(slurp(path));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    out[key_with_third && f.size() > 2 ? f[0] + "," + f[2] : f[0]] = f;
  }
  return out;
}

double num(const std::string& s) { return s.empty() ? NAN : std::stod(s); }

CompareOutput no_plot(const std::string& dir) { return {dir, "cgdem compare (test)", false}; }

}  // namespace

TEST(CompareRuns, MetricDifferencesAgainstTheFirstRunAndNaNIsMissing) {
  const std::string root = scratch_dir();
  const std::string a = make_run(root, "with_air",
                                 "fill_mass_kg,2\nfront_time_s,0.125\np_B_peak_Pa,15.5\nzero_kg,0\nzero_both_kg,0\n"
                                 "only_a,7\n");
  const std::string b = make_run(root, "vacuum",
                                 "fill_mass_kg,3\nfront_time_s,0.1\np_B_peak_Pa,nan\nzero_kg,4\nzero_both_kg,0\n"
                                 "only_b,1\n");
  for (const auto& d : {a, b}) write_diagnostics(d, 0, 10, {{"mass_in_die", [](double t) { return t; }}});
  const Comparison c = compare_runs({a, b}, {}, {});
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_EQ(c.runs[0].label, "with_air");
  EXPECT_EQ(c.runs[1].label, "vacuum");
  const std::string out = root + "/report";
  EXPECT_EQ(write_compare_outputs(c, no_plot(out)), "switched off (--no-plot)");

  auto m = rows(out + "/metrics_compare.csv");
  EXPECT_EQ(m["metric"],
            (std::vector<std::string>{"metric", "unit", "with_air", "vacuum", "diff:vacuum", "rel_diff:vacuum"}));
  // fill mass 2 -> 3: diff 1, relative 1/2.
  EXPECT_EQ(m["fill_mass_kg"][1], "kg");
  EXPECT_NEAR(num(m["fill_mass_kg"][2]), 2, kTol);
  EXPECT_NEAR(num(m["fill_mass_kg"][3]), 3, kTol);
  EXPECT_NEAR(num(m["fill_mass_kg"][4]), 1, kTol);
  EXPECT_NEAR(num(m["fill_mass_kg"][5]), 0.5, kTol);
  // front time 0.125 -> 0.1: -0.025 and -0.2.
  EXPECT_EQ(m["front_time_s"][1], "s");
  EXPECT_NEAR(num(m["front_time_s"][4]), -0.025, kTol);
  EXPECT_NEAR(num(m["front_time_s"][5]), -0.2, kTol);
  // NaN in the second run: the value and both differences are empty (missing), not numbers.
  EXPECT_EQ(m["p_B_peak_Pa"], (std::vector<std::string>{"p_B_peak_Pa", "Pa", "15.5", "", "", ""}));
  // Relative to 0: missing, unless both are 0.
  EXPECT_NEAR(num(m["zero_kg"][4]), 4, kTol);
  EXPECT_EQ(m["zero_kg"][5], "");
  EXPECT_EQ(m["zero_both_kg"][5], "0");
  // A metric only one run wrote: missing in the other.
  EXPECT_EQ(m["only_a"], (std::vector<std::string>{"only_a", "", "7", "", "", ""}));
  EXPECT_EQ(m["only_b"], (std::vector<std::string>{"only_b", "", "", "1", "", ""}));

  const std::string md = slurp(out + "/compare.md");
  EXPECT_NE(md.find("| p_B_peak_Pa | Pa | 15.5 | — | — | — |"), std::string::npos) << md;
  EXPECT_NE(md.find("| fill_mass_kg | kg | 2 | 3 | +1 | +50 % |"), std::string::npos) << md;
  EXPECT_EQ(md.find("nan"), std::string::npos) << "a NaN shown as a number";
  EXPECT_NE(md.find("Plots skipped: switched off (--no-plot)"), std::string::npos);
}

TEST(CompareRuns, CurvesAtFixedTimesAndL2DistancesMatchTheClosedForms) {
  const std::string root = scratch_dir();
  const std::string a = make_run(root, "a", "fill_mass_kg,1\n");
  const std::string b = make_run(root, "b", "fill_mass_kg,1\n");
  // Run a: t = 0 .. 0.3 s; run b: t = 0.05 .. 0.4 s (common range 0.05 .. 0.3 s).
  write_diagnostics(a, 0, 300,
                    {{"mass_in_die", [](double t) { return t; }},
                     {"transfer_rate", [](double) { return 1.0; }},
                     {"p_A", [](double t) { return 1 + t; }},
                     {"p_B", [](double t) { return t; }},
                     {"mass_in_shoe", [](double t) { return 1 - t; }},
                     {"bubbles", [](double) { return NAN; }}});
  write_diagnostics(b, 50, 400,
                    {{"mass_in_die", [](double t) { return 2 * t; }},
                     {"transfer_rate", [](double) { return 1.5; }},
                     {"p_A", [](double) { return NAN; }},  // in vacuum
                     {"p_B", [](double t) { return t + 0.1; }},
                     {"mass_in_shoe", [](double t) { return 1 - t; }},
                     {"bubbles", [](double) { return NAN; }},
                     {"Q_cavity", [](double t) { return 3 * t; }}});  // only in b
  const Comparison c = compare_runs({a, b}, {"air", "vac"}, {});
  const std::string out = root + "/report";
  write_compare_outputs(c, no_plot(out));
  EXPECT_NEAR(c.curves.t_lo, 0.05, kTol);
  EXPECT_NEAR(c.curves.t_hi, 0.3, kTol);
  EXPECT_EQ(c.curves.reference_points, 251u);  // a's samples 0.050, 0.051, ... 0.300
  EXPECT_EQ(c.curves.no_values, (std::vector<std::string>{"bubbles"}));

  // Sampled table: t = 0.06, 0.08, ... 0.30 (the multiples of 0.02 s in the common range).
  const CsvTable t = read_csv_table(out + "/curves_compare.csv");
  EXPECT_EQ(t.names, (std::vector<std::string>{"t_s", "air:mass_in_die_kg", "vac:mass_in_die_kg",
                                               "air:transfer_rate_kg_s", "vac:transfer_rate_kg_s", "air:p_A_Pa",
                                               "vac:p_A_Pa", "air:p_B_Pa", "vac:p_B_Pa", "air:mass_in_shoe_kg",
                                               "vac:mass_in_shoe_kg", "air:Q_cavity_m3_s", "vac:Q_cavity_m3_s"}));
  ASSERT_EQ(t.rows(), 13u);
  for (size_t j = 0; j < t.rows(); ++j) {
    const double tj = 0.06 + 0.02 * static_cast<double>(j);
    EXPECT_NEAR(t.col("t_s")[j], tj, kTol);
    EXPECT_NEAR(t.col("air:mass_in_die_kg")[j], tj, kTol);
    EXPECT_NEAR(t.col("vac:mass_in_die_kg")[j], 2 * tj, kTol);
    EXPECT_NEAR(t.col("vac:transfer_rate_kg_s")[j], 1.5, kTol);
    EXPECT_NEAR(t.col("air:p_A_Pa")[j], 1 + tj, kTol);
    EXPECT_TRUE(std::isnan(t.col("vac:p_A_Pa")[j]));
    EXPECT_NEAR(t.col("vac:mass_in_shoe_kg")[j], 1 - tj, kTol);
    EXPECT_TRUE(std::isnan(t.col("air:Q_cavity_m3_s")[j]));  // carried through, missing in air
    EXPECT_NEAR(t.col("vac:Q_cavity_m3_s")[j], 3 * tj, kTol);
  }

  // Distances on a's 251 samples, h = 1e-3 s, from 0.05 to 0.3 s:
  //   mass_in_die 2t vs t: D_2 = 1, max |d| = 0.3 at 0.3 s; transfer_rate 1.5 vs 1: D_2 = 0.5;
  //   p_B t + 0.1 vs t: D_2 = 0.1 sqrt((b - a) / T) with T the trapezoid sum of t^2,
  //   T = (b^3 - a^3)/3 + (b - a) h^2 / 6 (exact for a quadratic);
  //   mass_in_shoe identical: 0; p_A NaN in vac, Q_cavity absent in air: missing.
  auto d = rows(out + "/curves_distance.csv", true);
  EXPECT_EQ(d["curve,run"], (std::vector<std::string>{"curve", "unit", "run", "normalized_l2", "max_abs_diff",
                                                      "t_max_abs_diff_s", "samples"}));
  EXPECT_NEAR(num(d["mass_in_die,vac"][3]), 1, kTol);
  EXPECT_NEAR(num(d["mass_in_die,vac"][4]), 0.3, kTol);
  EXPECT_NEAR(num(d["mass_in_die,vac"][5]), 0.3, kTol);
  EXPECT_EQ(d["mass_in_die,vac"][6], "251");
  EXPECT_EQ(d["mass_in_die,vac"][1], "kg");
  EXPECT_NEAR(num(d["transfer_rate,vac"][3]), 0.5, kTol);
  EXPECT_NEAR(num(d["transfer_rate,vac"][4]), 0.5, kTol);
  const double lo = 0.05, hi = 0.3, h = 1e-3;
  const double T = (hi * hi * hi - lo * lo * lo) / 3 + (hi - lo) * h * h / 6;
  EXPECT_NEAR(num(d["p_B,vac"][3]), 0.1 * std::sqrt((hi - lo) / T), kTol);
  EXPECT_NEAR(num(d["p_B,vac"][4]), 0.1, kTol);
  EXPECT_NEAR(num(d["mass_in_shoe,vac"][3]), 0, kTol);
  EXPECT_EQ(d["p_A,vac"][3], "");
  EXPECT_EQ(d["p_A,vac"][6], "0");
  EXPECT_EQ(d["Q_cavity,vac"][1], "m^3/s");
  EXPECT_EQ(d["Q_cavity,vac"][3], "");
  EXPECT_EQ(d.count("bubbles,vac"), 0u);

  const std::string md = slurp(out + "/compare.md");
  EXPECT_NE(md.find("Common time range t = 0.05 to 0.3 s"), std::string::npos) << md;
  EXPECT_NE(md.find("| mass_in_die | kg | vac | 1 | 0.3 | 0.3 | 251 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| p_A | Pa | vac | — | — | — | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("### Q_cavity (m^3/s)"), std::string::npos);
  EXPECT_NE(md.find("No finite value in any run (left out): bubbles."), std::string::npos);
  EXPECT_EQ(md.find("nan"), std::string::npos);

  // --from/--to narrow the range; the distances follow (constant curves: unchanged).
  const Curves n = compare_curves(c.runs, {0.05, 0.1, 0.2});
  EXPECT_NEAR(n.t_lo, 0.1, kTol);
  EXPECT_NEAR(n.t_hi, 0.2, kTol);
  EXPECT_EQ(n.times.size(), 3u);  // 0.10, 0.15, 0.20
  EXPECT_EQ(n.reference_points, 101u);
  EXPECT_NEAR(n.curves[1].l2[1], 0.5, kTol);
}

TEST(CompareRuns, RestartedRowsAreSupersededAndUnitsComeFromTheNames) {
  const std::string root = scratch_dir();
  const std::string a = make_run(root, "a", "x,1\n");
  spit(a + "/diagnostics.csv", "# run\nt,mass_in_die\n0,0\n0.1,1\n0.2,99\n0.3,99\n# restart\n0.2,2\n0.3,3\n");
  const CompareRun r = read_compare_run(a, "a");
  EXPECT_EQ(r.diagnostics.col("t"), (std::vector<double>{0, 0.1, 0.2, 0.3}));
  EXPECT_EQ(r.diagnostics.col("mass_in_die"), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(metric_unit("transfer_rate_peak_kg_s"), "kg/s");
  EXPECT_EQ(metric_unit("mean_impact_velocity_m_s"), "m/s");
  EXPECT_EQ(metric_unit("bubble_volume_peak_m3"), "m^3");
  EXPECT_EQ(metric_unit("p_A_mean_Pa"), "Pa");
  EXPECT_EQ(metric_unit("particles"), "");
  EXPECT_EQ(column_with_unit("t"), "t_s");
  EXPECT_EQ(column_with_unit("transfer_rate"), "transfer_rate_kg_s");
  EXPECT_EQ(column_with_unit("p_C"), "p_C_Pa");
  EXPECT_EQ(column_with_unit("V_bubbles"), "V_bubbles_m3");
  EXPECT_EQ(column_with_unit("impacts"), "impacts");
  EXPECT_EQ(folder_name("out/with_air/"), "with_air");
}

TEST(CompareRuns, ResolvedConfigurationKeysThatDifferAndTheRevision) {
  const std::string root = scratch_dir();
  const std::string a = make_run(root, "air", "x,1\n");
  const std::string b = make_run(root, "vac", "x,1\n");
  const std::string c3 = make_run(root, "noconf", "x,1\n");
  for (const auto& d : {a, b, c3}) write_diagnostics(d, 0, 10, {{"mass_in_die", [](double t) { return t; }}});
  const std::string common =
      "[time]\nend = 0.3\n[[diagnostics.pressure_cell]]\nname = \"A\"\nmax = [1.0, 2.0, 3.0]\n"
      "[[diagnostics.pressure_cell]]\nname = \"B\"\n";
  spit(a + "/config.resolved.toml",
       "# cgdem abc123 resolved configuration of cases/x.toml\n[air]\nenabled = true\n"
       "dx = 0.0006\n[output]\ndir = \"out/air\"\n" +
           common + "max = [1.0, 2.0, 4.0]\n");
  spit(b + "/config.resolved.toml",
       "# cgdem abc124-dirty resolved configuration of cases/x.toml\n[air]\nenabled = "
       "false\ndx = 0.0006\n[output]\ndir = \"out/vac\"\n" +
           common + "max = [1.0, 2.0, 5.0]\n");
  const Comparison c = compare_runs({a, b, c3}, {}, {});
  EXPECT_EQ(c.runs[0].revision, "abc123");
  EXPECT_EQ(c.runs[1].revision, "abc124-dirty");
  EXPECT_EQ(c.runs[2].revision, "def456");  // from diagnostics.csv's comment line
  EXPECT_EQ(c.runs[0].case_file, "cases/x.toml");
  EXPECT_FALSE(c.runs[2].has_config);
  ASSERT_EQ(c.config.size(), 3u);
  EXPECT_EQ(c.config[0].key, "air.enabled");
  EXPECT_EQ(c.config[0].values[0], "true");
  EXPECT_EQ(c.config[0].values[1], "false");
  EXPECT_EQ(c.config[0].values[2], std::nullopt);
  EXPECT_EQ(c.config[1].key, "diagnostics.pressure_cell[1].max");
  EXPECT_EQ(c.config[1].values[0], "[1.0, 2.0, 4.0]");
  EXPECT_EQ(c.config[1].values[1], "[1.0, 2.0, 5.0]");
  EXPECT_EQ(c.config[2].key, "output.dir");
  const std::string out = root + "/report";
  write_compare_outputs(c, no_plot(out));
  const std::string md = slurp(out + "/compare.md");
  EXPECT_NE(md.find("| `air.enabled` | true | false | — |"), std::string::npos) << md;
  EXPECT_NE(md.find("No config.resolved.toml in `" + c3 + "`"), std::string::npos) << md;
  EXPECT_NE(md.find("| abc124-dirty | `cases/x.toml` |"), std::string::npos) << md;
  // Three runs: a difference and a relative difference per run after the first.
  auto m = rows(out + "/metrics_compare.csv");
  EXPECT_EQ(m["metric"], (std::vector<std::string>{"metric", "unit", "air", "vac", "noconf", "diff:vac", "diff:noconf",
                                                   "rel_diff:vac", "rel_diff:noconf"}));
}

TEST(CompareRuns, BadInputNamesTheFolderAndTheFile) {
  const std::string root = scratch_dir();
  const std::string good = make_run(root, "good", "x,1\n");
  write_diagnostics(good, 0, 10, {{"mass_in_die", [](double t) { return t; }}});
  const std::string later = make_run(root, "later", "x,1\n");
  write_diagnostics(later, 20, 30, {{"mass_in_die", [](double t) { return t; }}});
  const std::string nometrics = root + "/nometrics";
  std::filesystem::create_directories(nometrics);
  write_diagnostics(nometrics, 0, 10, {{"mass_in_die", [](double t) { return t; }}});
  const std::string nodiag = make_run(root, "nodiag", "x,1\n");
  const std::string not_t = make_run(root, "not_t", "x,1\n");
  spit(not_t + "/diagnostics.csv", "time,mass_in_die\n0,0\n");

  auto err = [&](const std::vector<std::string>& dirs, const std::vector<std::string>& labels = {}) {
    return error_of([&] { compare_runs(dirs, labels, {}); });
  };
  EXPECT_EQ(err({good, root + "/absent"}), "compare: run folder '" + root + "/absent' does not exist");
  EXPECT_NE(err({good, nometrics}).find("run folder '" + nometrics + "' has no metrics.csv"), std::string::npos);
  EXPECT_NE(err({nodiag, good}).find("run folder '" + nodiag + "' has no diagnostics.csv"), std::string::npos);
  EXPECT_NE(err({good, not_t}).find(not_t + "/diagnostics.csv: no column 't'"), std::string::npos);
  EXPECT_NE(err({good}).find("give at least two run folders (got 1)"), std::string::npos);
  const std::string disjoint = err({good, later});
  EXPECT_NE(disjoint.find("no common time range"), std::string::npos) << disjoint;
  EXPECT_NE(disjoint.find("good 0 to 0.01 s, later 0.02 to 0.03 s"), std::string::npos) << disjoint;
  EXPECT_NE(err({good, good}).find("have the same label 'good'"), std::string::npos);
  EXPECT_NE(err({good, good}, {"one"}).find("--labels: 1 label(s) for 2 run folders"), std::string::npos);
  EXPECT_NE(error_of([&] { compare_runs({good, good}, {"a", "b"}, {0.0, {}, {}}); }).find("--dt"), std::string::npos);
  EXPECT_EQ(err({good, good}, {"a", "b"}), "(no error)");
}
