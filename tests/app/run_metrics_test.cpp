// metrics.csv of a die-filling run (app/run_metrics.hpp) on synthetic diagnostics.csv files:
//   * the filling window of the paper's geometry: the die opens at 0.0505 s (the cavity's
//     leading edge 5 mm before the mouth, 1 ms ramp to 0.1 m/s) and closes at 0.2505 s;
//   * a start-up spike before the die opens (p_C 50 Pa at 0.8 ms) is not the peak: the
//     filling maximum (20 Pa at 0.19 s) is, and the window is written as window_from_s /
//     window_to_s;
//   * old (t, p_C) and new (t_s, p_C_Pa, '#' lines after the column line) layouts give the
//     same metrics;
//   * without air the pressure and bubble metrics are left out (not computed), as is a cell
//     with no finite value and every windowed peak of a run that ends before the die opens.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "app/run_metrics.hpp"
#include "io/metrics.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem::app {
namespace {

using io::test::scratch_dir;
using io::test::spit;

// Rows every 0.2 ms from -0.01 s to t_end: a start-up spike of p_C (50 Pa, 0.8 ms) and of
// the rate, a broad filling maximum of p_C (20 Pa at 0.19 s), p_B = half of p_C's bump, p_X
// NaN throughout (a box without air), a bubble from 0.15 s.
std::string diagnostics(bool new_layout, double t_end = 0.3) {
  std::string s = new_layout ? "t_s,mass_in_die_kg,transfer_rate_kg_per_s,impacts,p_B_Pa,p_C_Pa,p_X_Pa,mass_in_shoe_kg,"
                               "V_bubble_max_m3,V_bubbles_shoe_m3\n# cgdem test\n# t_s: s, time\n"
                             : "# cgdem test\nt,mass_in_die,transfer_rate,impacts,p_B,p_C,p_X,mass_in_shoe,"
                               "V_bubble_max,V_bubbles_shoe\n";
  for (int i = -50; i * 2e-4 <= t_end + 1e-12; ++i) {
    const double t = i * 2e-4;
    const double bump = 20 * std::exp(-0.5 * std::pow((t - 0.19) / 0.03, 2));
    const double spike = std::fabs(t - 0.0008) < 1e-9 ? 50.0 : 0.0;
    const double rate = std::fabs(t - 0.0008) < 1e-9 ? 0.5 : (t > 0.05 && t < 0.25 ? 0.01 * std::sin(t * 10) : 0.0);
    const double mass = t > 0.05 ? 1e-3 * (t - 0.05) : 0.0;
    const double bubble = t >= 0.15 ? 1e-9 * (1 + (t - 0.15)) : 0.0;
    s += fmt::format("{:.9g},{:.9g},{:.9g},0,{:.9g},{:.9g},nan,{:.9g},{:.9g},{:.9g}\n", t, mass, rate, bump / 2,
                     bump + spike, 1e-4, bubble, bubble / 2);
  }
  return s;
}

double value(const io::Metrics& m, const std::string& name) { return io::metric(m, name, "metrics"); }

TEST(RunMetrics, FillingWindowOfThePapersGeometry) {
  const geometry::DieFillingParams die;  // defaults: the paper's Case 1-3 geometry
  const FillingWindow w = filling_window(die);
  std::printf("filling window: die opens at %.9g s (want 0.0505), closes at %.9g s (want 0.2505)\n", w.from, w.to);
  EXPECT_NEAR(w.from, 0.0505, 1e-9);
  EXPECT_NEAR(w.to, 0.2505, 1e-9);
  geometry::DieFillingParams still = die;
  still.shoe_speed = 0;
  EXPECT_TRUE(std::isinf(filling_window(still).from));
  geometry::DieFillingParams over = die;
  over.cavity_x0 = die.mouth_x0 - 2e-3;  // already over the mouth at t = 0
  EXPECT_EQ(filling_window(over).from, 0.0);
}

TEST(RunMetrics, PeaksAreTakenOverTheFillingWindowNotTheStartUpSpike) {
  const std::string dir = scratch_dir();
  const DieRun run{geometry::DieFillingParams{}, true};
  for (bool new_layout : {false, true}) {
    const std::string path = dir + (new_layout ? "/new.csv" : "/old.csv");
    spit(path, diagnostics(new_layout));
    const io::Metrics m = die_metrics(path, std::make_pair(0.087, 0.36), run);
    std::printf("%s layout: window %.6g to %.6g s; p_C peak %.6g Pa at %.6g s (the spike: 50 Pa at 0.0008 s); p_B "
                "peak %.6g Pa at %.6g s; rate peak %.4g kg/s at %.4g s; p_C mean %.6g Pa\n",
                new_layout ? "new" : "old", value(m, "window_from_s"), value(m, "window_to_s"), value(m, "p_C_peak_Pa"),
                value(m, "p_C_peak_time_s"), value(m, "p_B_peak_Pa"), value(m, "p_B_peak_time_s"),
                value(m, "transfer_rate_peak_kg_s"), value(m, "transfer_rate_peak_time_s"), value(m, "p_C_mean_Pa"));
    EXPECT_NEAR(value(m, "window_from_s"), 0.0505, 1e-9);
    EXPECT_NEAR(value(m, "window_to_s"), 0.2505, 1e-9);
    EXPECT_NEAR(value(m, "p_C_peak_Pa"), 20.0, 1e-6);  // the bump's top, sampled on its centre
    EXPECT_NEAR(value(m, "p_C_peak_time_s"), 0.19, 1e-9);
    EXPECT_NEAR(value(m, "p_B_peak_Pa"), 10.0, 1e-6);
    EXPECT_LT(value(m, "transfer_rate_peak_kg_s"), 0.011);  // not the 0.5 kg/s start-up row
    EXPECT_GT(value(m, "transfer_rate_peak_time_s"), 0.0505);
    // The mean over the window: the bump's mean over 0.0506 .. 0.2504 s (1000 rows).
    double sum = 0;
    int n = 0;
    for (int i = 253; i * 2e-4 <= 0.2505; ++i, ++n) sum += 20 * std::exp(-0.5 * std::pow((i * 2e-4 - 0.19) / 0.03, 2));
    EXPECT_NEAR(value(m, "p_C_mean_Pa"), sum / n, 1e-6);
    EXPECT_NEAR(value(m, "bubble_volume_peak_time_s"), 0.2504, 1e-9);  // the last row before 0.2505 s
    EXPECT_EQ(value(m, "front_time_s"), 0.087);
    EXPECT_NEAR(value(m, "fill_mass_kg"), 1e-3 * 0.25, 1e-12);
    EXPECT_EQ(value(m, "shoe_mass_end_kg"), 1e-4);
    // p_X has no finite value: not computed, left out.
    EXPECT_FALSE(io::has_metric(m, "p_X_peak_Pa"));
    EXPECT_FALSE(io::has_metric(m, "p_X_mean_Pa"));
  }
  // Without the geometry the window is t >= 0 as before, and the spike would be the peak:
  // the reason for the window.
  const io::Metrics old = die_metrics(dir + "/old.csv", std::nullopt);
  std::printf("window t >= 0 (no geometry): p_C peak %.6g Pa at %.6g s\n", value(old, "p_C_peak_Pa"),
              value(old, "p_C_peak_time_s"));
  EXPECT_EQ(value(old, "window_from_s"), 0.0);
  EXPECT_NEAR(value(old, "p_C_peak_time_s"), 0.0008, 1e-12);
}

TEST(RunMetrics, WithoutAirPressuresAreLeftOutNotNaN) {
  const std::string dir = scratch_dir();
  spit(dir + "/diagnostics.csv", diagnostics(true));
  const io::Metrics m = die_metrics(dir + "/diagnostics.csv", std::nullopt, DieRun{geometry::DieFillingParams{}, false});
  io::write_metrics(dir + "/metrics.csv", m);
  const io::Metrics back = io::read_metrics(dir + "/metrics.csv");
  std::string names;
  for (const auto& [k, v] : back) names += k + " ";
  std::printf("vacuum metrics: %s\n", names.c_str());
  for (const char* n : {"p_B_peak_Pa", "p_B_peak_time_s", "p_B_mean_Pa", "p_C_peak_Pa", "bubble_volume_peak_m3",
                        "bubble_in_shoe_peak_time_s"}) {
    EXPECT_FALSE(io::has_metric(back, n)) << n;
    EXPECT_TRUE(io::may_be_left_out(n)) << n;
  }
  for (const auto& [k, v] : back)
    if (k != "front_time_s" && k != "mean_impact_velocity_m_s") EXPECT_TRUE(std::isfinite(v)) << k;
  EXPECT_TRUE(io::has_metric(back, "transfer_rate_peak_kg_s"));
  EXPECT_TRUE(io::has_metric(back, "window_from_s"));
  EXPECT_FALSE(io::may_be_left_out("fill_mass_kg"));
  EXPECT_FALSE(io::may_be_left_out("no_such_metric"));
}

TEST(RunMetrics, RunEndingBeforeTheDieOpensHasNoPeaks) {
  const std::string dir = scratch_dir();
  spit(dir + "/diagnostics.csv", diagnostics(false, 0.03));
  const io::Metrics m = die_metrics(dir + "/diagnostics.csv", std::nullopt, DieRun{geometry::DieFillingParams{}, true});
  std::printf("run to 0.03 s: window %.6g to %.6g s (empty), %zu metrics\n", value(m, "window_from_s"),
              value(m, "window_to_s"), m.size());
  EXPECT_GT(value(m, "window_from_s"), value(m, "window_to_s"));
  for (const char* n : {"transfer_rate_peak_kg_s", "p_C_peak_Pa", "p_C_mean_Pa", "bubble_volume_peak_m3"})
    EXPECT_FALSE(io::has_metric(m, n)) << n;
  EXPECT_TRUE(io::has_metric(m, "fill_mass_kg"));
}

}  // namespace
}  // namespace cgdem::app
