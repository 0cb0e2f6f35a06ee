// Reading a run's pressure series for `cgdem spectrum` (scaling/spectrum_series.hpp) and
// the run-level analysis (scaling/spectrum_report.hpp): column discovery, restarts,
// uniformity, resampling, segment lengths, overlay of runs, and every bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/error.hpp"
#include "scaling/spectrum_report.hpp"
#include "scaling/spectrum_series.hpp"
#include "tests/error_of.hpp"
#include "tests/io/scratch.hpp"

using namespace cgdem::scaling;
using cgdem::io::test::scratch_dir;
using cgdem::io::test::slurp;
using cgdem::io::test::spit;

namespace {

using cgdem::test::error_of;

// A run folder whose diagnostics.csv has p_A = sin(2 pi fA t), p_B = 0.5 sin(2 pi fB t),
// n rows from t0 every dt (the time written as n*dt, as the run loop accumulates it).
std::string synthetic_run(const std::string& dir, double dt, int n, double fA, double fB, double t0 = 0) {
  std::filesystem::create_directories(dir);
  std::string s = "# synthetic\nt,mass_in_die,transfer_rate,impacts,p_A,p_B\n";
  for (int i = 0; i < n; ++i) {
    const double t = t0 + i * dt;
    s += fmt::format("{:.10g},0,0,0,{:.10g},{:.10g}\n", t, std::sin(2 * std::numbers::pi * fA * t),
                     0.5 * std::sin(2 * std::numbers::pi * fB * t));
  }
  spit(dir + "/diagnostics.csv", s);
  return dir;
}

TEST(SpectrumSeries, PressureColumnsByPrefixAndRestartedRowsSuperseded) {
  const std::string dir = scratch_dir();
  spit(dir + "/diagnostics.csv",
       "# run\nt,x,p_left,p_right\n0,9,1,2\n0.5,9,3,4\n1,9,5,6\n1.5,9,7,8\n# restart\n1,9,50,60\n1.5,9,70,80\n2,9,90,"
       "100\n");
  const PressureSeries s = read_pressure_series(dir);
  ASSERT_EQ(s.cells, (std::vector<std::string>{"left", "right"}));
  EXPECT_EQ(s.t, (std::vector<double>{0, 0.5, 1, 1.5, 2}));
  EXPECT_EQ(s.p[0], (std::vector<double>{1, 3, 50, 70, 90}));
  EXPECT_EQ(s.p[1], (std::vector<double>{2, 4, 60, 80, 100}));
  EXPECT_EQ(uniform_interval(s), 0.5);

  const PressureSeries r = select(s, {"right"}, 0.4, 1.6);
  EXPECT_EQ(r.t, (std::vector<double>{0.5, 1, 1.5}));
  EXPECT_EQ(r.p[0], (std::vector<double>{4, 60, 80}));
  const std::string unknown = error_of([&] { select(s, {"C"}, {}, {}); });
  EXPECT_NE(unknown.find("--cells: " + s.source + " has no cell 'C' (it has left,right)"), std::string::npos) << unknown;
  EXPECT_NE(error_of([&] { select(s, {}, 5.0, 6.0); }).find("--from/--to"), std::string::npos);
}

TEST(SpectrumSeries, NonUniformSamplingIsAnErrorAndResamplingIsExactForLines) {
  const std::string dir = scratch_dir();
  // As in a real run: 0.001 steps, one interval of 0.0011 (an output that waited a step).
  std::string text = "# run\nt,p_A\n";
  std::vector<double> t = {-0.002, -0.001, 6.90148893e-16, 0.001, 0.002, 0.0031, 0.0041, 0.0051};
  for (double v : t) text += fmt::format("{:.10g},{:.10g}\n", v, 3.0 + 2.0 * v);
  spit(dir + "/diagnostics.csv", text);
  const PressureSeries s = read_pressure_series(dir);
  const std::string msg = error_of([&] { uniform_interval(s); });
  std::printf("%s\n", msg.c_str());
  EXPECT_NE(msg.find("sampling is not uniform: t = 0.002 -> 0.0031 s is an interval of 0.0011 s"), std::string::npos);
  EXPECT_NE(msg.find("--dt"), std::string::npos);
  EXPECT_EQ(uniform_interval(select(s, {}, {}, 0.0025)), 0.001);  // 7e-16 of jitter is fine

  const PressureSeries r = resample(s, 0.001);
  ASSERT_EQ(r.t.size(), 8u);  // -0.002 .. 0.005
  double worst = 0;
  for (size_t i = 0; i < r.t.size(); ++i) worst = std::max(worst, std::abs(r.p[0][i] - (3.0 + 2.0 * r.t[i])));
  std::printf("resampled line: max error %.2e (tol 1e-12)\n", worst);
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(uniform_interval(r, 1e-9), 0.001, 1e-15);
}

TEST(SpectrumSeries, BadFilesAreClearErrors) {
  const std::string dir = scratch_dir();
  EXPECT_NE(error_of([&] { read_pressure_series(dir + "/nope"); }).find("run folder '" + dir + "/nope' does not exist"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_pressure_series(dir); }).find("cannot read '" + dir + "/diagnostics.csv'"),
            std::string::npos);
  spit(dir + "/diagnostics.csv", "# run\nt,mass_in_die\n0,1\n1,2\n");
  EXPECT_NE(error_of([&] { read_pressure_series(dir); }).find("no pressure column (p_<cell>)"), std::string::npos);
  spit(dir + "/diagnostics.csv", "t,p_A\n0,1\n1,x2\n");
  EXPECT_NE(error_of([&] { read_pressure_series(dir); }).find("diagnostics.csv:3: 'x2' is not a number"),
            std::string::npos);
  spit(dir + "/diagnostics.csv", "t,p_A\n0,1\n1,nan\n");
  EXPECT_NE(error_of([&] { read_pressure_series(dir); }).find("non-finite"), std::string::npos);
  spit(dir + "/diagnostics.csv", "t,p_A\n0,1,2\n");
  EXPECT_NE(error_of([&] { read_pressure_series(dir); }).find("3 values, the column line has 2"), std::string::npos);
}

TEST(SpectrumSeries, SegmentLengthInSamplesOrSeconds) {
  EXPECT_EQ(segment_samples("256", 1e-3, 1000, 0.5), 256);
  EXPECT_EQ(segment_samples("0.256s", 1e-3, 1000, 0.5), 256);
  EXPECT_EQ(segment_samples("0.0128s", 2e-4, 1000, 0.5), 64);
  EXPECT_EQ(segment_samples("", 1e-3, 361, 0.5), 64);  // 361 / 4.5 = 80 -> 64, K = 10
  EXPECT_EQ(segment_samples("", 1e-3, 361, 0.0), 32);  // 361 / 8 = 45 -> 32, K = 11
  EXPECT_NE(error_of([] { segment_samples("0.1", 1e-3, 1000, 0.5); }).find("--segment: '0.1' is neither"),
            std::string::npos);
  EXPECT_NE(error_of([] { segment_samples("2000", 1e-3, 1000, 0.5); }).find("longer than the 1000 samples"),
            std::string::npos);
  EXPECT_NE(error_of([] { segment_samples("", 1e-3, 30, 0.5); }).find("too few"), std::string::npos);
}

// Two runs at different sampling intervals: an error unless resampled onto --dt; then one
// frequency grid, and each run's dominant frequencies where its sines are.
TEST(SpectrumReport, RunsOverlaidOnOneGrid) {
  const std::string dir = scratch_dir();
  const std::string a = synthetic_run(dir + "/l=1", 5e-4, 1600, 250.0, 62.5);
  const std::string b = synthetic_run(dir + "/l=2", 2.5e-4, 3200, 187.5, 62.5);
  SpectrumSettings s;
  s.segment = "0.064s";
  s.plot = false;
  EXPECT_NE(error_of([&] { analyse_runs({a, b}, {}, s); }).find("sampled at different intervals"), std::string::npos);
  s.dt = 5e-4;
  const SpectrumAnalysis r = spectrum_report({a, b}, {}, s, dir + "/out");
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_EQ(r.params.segment, 128);
  EXPECT_EQ(r.runs[0].label, "l=1");
  const double df = r.params.fs / r.params.segment;  // 15.625 Hz
  EXPECT_EQ(r.runs[0].peaks[0][0].f, 250.0);
  EXPECT_EQ(r.runs[0].peaks[1][0].f, 62.5);
  EXPECT_EQ(r.runs[1].peaks[0][0].f, 187.5);
  // Band powers: A^2/2 = 0.5 and 0.125 (on-bin sines, Hann). The second run's grid points
  // are every other one of its samples, so its resampling is exact too.
  std::printf("df %.4f Hz; band powers %.8f (0.5), %.8f (0.125), resampled %.8f (0.5); tol 1e-6\n", df,
              r.runs[0].peaks[0][0].band_power, r.runs[0].peaks[1][0].band_power, r.runs[1].peaks[0][0].band_power);
  EXPECT_NEAR(r.runs[0].peaks[0][0].band_power, 0.5, 1e-6);
  EXPECT_NEAR(r.runs[0].peaks[1][0].band_power, 0.125, 1e-6);
  EXPECT_NEAR(r.runs[1].peaks[0][0].band_power, 0.5, 1e-6);

  const std::string psd = slurp(dir + "/out/psd.csv");
  EXPECT_NE(psd.find("\nf_Hz,l=1:A,l=1:B,l=2:A,l=2:B\n"), std::string::npos);
  EXPECT_NE(slurp(dir + "/out/coherence.csv").find("\nf_Hz,l=1:A-B,l=2:A-B\n"), std::string::npos);
  EXPECT_NE(slurp(dir + "/out/peaks.csv").find("l=1,A,1,250,"), std::string::npos);
  EXPECT_NE(slurp(dir + "/out/spectrum.md").find("| frequency resolution | df = fs / L = 15.625 Hz"), std::string::npos);
  EXPECT_EQ(cgdem::io::test::count_temporaries(dir + "/out"), 0);

  EXPECT_NE(error_of([&] { analyse_runs({a, b}, {"x"}, s); }).find("--labels: 1 label(s) for 2 run folder(s)"),
            std::string::npos);
  s.cells = {"B", "Q"};
  EXPECT_NE(error_of([&] { analyse_runs({a}, {}, s); }).find("has no cell 'Q'"), std::string::npos);
}

}  // namespace
