// diagnostics.csv on a uniform grid (app/run_schedule.hpp): the row interval rounded up to a
// whole multiple of at least the largest step; steps that end on a row time write it, steps
// that pass one get it interpolated, whatever their lengths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "app/run_schedule.hpp"

using namespace cgdem;
using namespace cgdem::app;

namespace {

DemCase small_case(double t_start, double t_end) {
  DemCase c;
  c.t_start = t_start;
  c.t_end = t_end;
  c.dem.dt = 1e-6;
  return c;
}

DiagnosticsSpec every(double interval) {
  DiagnosticsSpec d;
  d.enabled = true;
  d.interval = interval;
  return d;
}

}  // namespace

TEST(OutputSchedule, DiagnosticsRowsOnAUniformGridWhateverTheSteps) {
  // Case 1-3: diagnostics.interval 1e-4, fluid steps of 2e-4 -> rows every 2e-4 s from -0.06.
  const DemCase c = small_case(-0.06, 0.0);
  EXPECT_NEAR(OutputSchedule(c, every(1e-4), -0.06, 2e-4).diagnostics_interval(), 2e-4, 1e-18);
  EXPECT_NEAR(OutputSchedule(c, every(1e-3), -0.06, 2e-4).diagnostics_interval(), 1e-3, 1e-18);
  EXPECT_NEAR(OutputSchedule(c, every(1e-4), -0.06, 1.5e-4).diagnostics_interval(), 2e-4, 1e-18);
  EXPECT_NEAR(OutputSchedule(c, every(1e-4), -0.06).diagnostics_interval(), 1e-4, 1e-18);  // vacuum

  // Steps of 2e-4 (200 DEM steps), then shortened ones (173 DEM steps, as by the CFL limit),
  // then 2e-4 again: every row time is reached once, landing or passed, in order.
  OutputSchedule s(c, every(1e-4), -0.06, 2e-4);
  std::vector<double> rows;  // times of the rows written, as run_case writes them
  long passed = 0, landed = 0;
  long k = 0;  // DEM steps since t_start
  double worst = 0;
  auto step = [&](long n) {
    const double t0 = -0.06 + 1e-6 * static_cast<double>(k), t1 = -0.06 + 1e-6 * static_cast<double>(k + n);
    const bool passes = s.passes_diagnostics(t0, t1);
    k += n;
    const OutputSchedule::Due due = s.after_step(t1);
    EXPECT_EQ(passes, !due.diagnostics_passed.empty()) << "at t = " << t1;
    for (double tk : due.diagnostics_passed) rows.push_back(tk), ++passed;
    if (due.diagnostics) rows.push_back(t1), ++landed;
  };
  for (int i = 0; i < 20; ++i) step(200);
  for (int i = 0; i < 30; ++i) step(173);
  while (!s.finished(-0.06 + 1e-6 * static_cast<double>(k))) step(200);
  // Row j on the grid -0.06 + (j + 1) 2e-4 (the row at t_start is written before the loop),
  // but the last: the final state.
  for (size_t j = 0; j + 1 < rows.size(); ++j)
    worst = std::max(worst, std::fabs(rows[j] - (-0.06 + 2e-4 * static_cast<double>(j + 1))));
  std::printf("rows %zu (landed %ld, interpolated %ld), last at %.9g s; worst deviation from the grid %.3g s "
              "(tol 1e-9 s)\n", rows.size(), landed, passed, rows.back(), worst);
  EXPECT_GT(passed, 20);
  EXPECT_LT(worst, 1e-9);
  // 9,190 DEM steps, then steps of 200 overshoot t_end = 0 to 0.00019 s: the final state.
  EXPECT_NEAR(rows.back(), 1.9e-4, 1e-12);
  EXPECT_EQ(rows.size(), 301u);  // -0.0598 .. 0 every 2e-4 s, and the final state
}

TEST(OutputSchedule, InterpolatedRowIsLinearWithCountsFromTheNearerRow) {
  DiagnosticsRow a, b;
  a.t = 1.0, b.t = 2.0;
  a.mass_in_die = 10, b.mass_in_die = 20;
  a.pressure = {1.0, std::nan("")}, b.pressure = {3.0, 5.0};
  a.impacts = 4, b.impacts = 9;
  a.bubbles = 1, b.bubbles = 2;
  const DiagnosticsRow r = interpolate_row(a, b, 1.25);
  std::printf("at t = 1.25: mass %g (want 12.5), p_A %g (want 1.5), p_B %g (want nan), impacts %ld (want 4)\n",
              r.mass_in_die, r.pressure[0], r.pressure[1], r.impacts);
  EXPECT_EQ(r.t, 1.25);
  EXPECT_DOUBLE_EQ(r.mass_in_die, 12.5);
  EXPECT_DOUBLE_EQ(r.pressure[0], 1.5);
  EXPECT_TRUE(std::isnan(r.pressure[1]));
  EXPECT_EQ(r.impacts, 4);
  EXPECT_EQ(r.bubbles, 1);
  EXPECT_EQ(interpolate_row(a, b, 1.75).impacts, 9);
}

// timings.csv: the report's phase names become identifiers, and a run's rows add up: the
// run's "other" is its wall minus every group's phases, so the groups and "other" sum to
// the wall exactly as the final report's "wall = DEM + coupling + air + output + other".
TEST(Timings, RowsOfARunAddUpToItsWall) {
  const std::pair<const char*, const char*> names[] = {
      {"air -> parcels", "air_to_parcels"}, {"ghosts, face eps", "ghosts_face_eps"},
      {"advection+viscous", "advection_viscous"}, {"IBM fractions", "ibm_fractions"},
      {"neighbour lists", "neighbour_lists"}, {"  ", "unnamed"}};
  for (const auto& [name, want] : names) {
    std::printf("'%s' -> '%s' (want '%s')\n", name, phase_identifier(name).c_str(), want);
    EXPECT_EQ(phase_identifier(name), want);
  }
  PhaseTimers dem, output;
  dem.add(dem.id("contact forces"), 2.5), dem.add(dem.id("contact forces"), 0.5), dem.add(dem.id("integrate"), 1.0);
  output.add(output.id("CSV series"), 0.25);
  RunPiece piece;
  piece.t_start = 0.01, piece.t_end = 0.03, piece.threads = 2, piece.wall = 5.0, piece.set_up = 1.5;
  piece.dem_steps = 20000, piece.list_builds = 7, piece.particles = 100, piece.peak_rss_mib = 512.25;
  const std::string rows = timings_rows(piece, {{"dem", &dem}, {"output", &output}});
  std::printf("%s", rows.c_str());
  const size_t fields = timings_columns().size();
  double groups = 0, other = -1, wall = -1;
  int n = 0;
  for (size_t a = 0; a < rows.size(); ++n) {
    const size_t b = rows.find('\n', a);
    ASSERT_NE(b, std::string::npos);
    std::vector<std::string> f;
    for (size_t c = a; c <= b;) {
      const size_t d = std::min(rows.find(',', c), b);
      f.push_back(rows.substr(c, d - c));
      c = d + 1;
    }
    ASSERT_EQ(f.size(), fields);
    EXPECT_EQ(f[0], "0.03");
    EXPECT_EQ(f[1], "0.01");
    EXPECT_EQ(f[9], "20000");
    EXPECT_EQ(f[13], "512.2");  // MiB, one decimal ({:.1f} rounds 512.25 half to even)
    const double s = std::stod(f[7]);
    if (f[5] == "run" && f[6] == "wall") wall = s;
    if (f[5] == "run" && f[6] == "other") other = s;
    if (f[5] != "run") groups += s;
    if (f[6] == "contact_forces") EXPECT_EQ(f[8], "2");  // calls
    a = b + 1;
  }
  std::printf("%d rows; groups %.3f s + other %.3f s = %.3f s, wall %.3f s\n", n, groups, other, groups + other, wall);
  EXPECT_EQ(n, 6);  // wall, set_up, other, 2 DEM phases, 1 output phase
  EXPECT_DOUBLE_EQ(groups + other, wall);
  EXPECT_DOUBLE_EQ(other, 0.75);
}
