// Die-filling diagnostics against hand-computed values: mass in the die and its transfer
// rate, first arrivals at the stepped floor and the front's mean impact speed, gauge
// pressure of the measurement cells (the still-air hydrostatic pressure reads 0).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "diagnostics/die_diagnostics.hpp"
#include "app/run_metrics.hpp"
#include "fluid/fluid_state.hpp"

using namespace cgdem;
using namespace cgdem::app;
using namespace cgdem::diagnostics;

namespace {

DiagnosticsSpec spec() {
  DiagnosticsSpec s;
  s.enabled = true;  // mouth x 37..47 mm, y 6..36 mm, table top 14 mm, type 1
  s.die.table_top = 14e-3;
  s.rate_window = 2e-3;
  s.impact_window = 1e-3;
  s.cells = {{"A", {40e-3, 20e-3, 8e-3}, {41.2e-3, 21.2e-3, 9.2e-3}}};
  return s;
}

Species powder() { return {"p", 125e-6, 3, 1500}; }

}  // namespace

TEST(DieDiagnostics, MassInDieAndTransferRate) {
  const Species sp = powder();
  DieDiagnostics d(spec(), {sp.mass()}, {sp.diameter()});
  Particles p;
  // One parcel enters the die every 0.1 ms: the rate is m / 1e-4 s.
  for (int n = 0; n <= 40; ++n) {
    p.add(n, 0, sp, {42e-3, 20e-3, 13e-3});       // inside the mouth, below the table top
    p.add(1000 + n, 0, sp, {30e-3, 20e-3, 15e-3});  // still in the shoe: not counted
    d.observe(n * 1e-4, p);
  }
  auto r = d.row(40e-4, p, nullptr, nullptr);
  const double want_mass = 41 * sp.mass(), want_rate = sp.mass() / 1e-4;
  std::printf("[ diagnostics ] mass in die %.6e kg (want %.6e), rate %.6e kg/s (want %.6e)\n", r.mass_in_die,
              want_mass, r.transfer_rate, want_rate);
  EXPECT_NEAR(r.mass_in_die, want_mass, 1e-12 * want_mass);
  EXPECT_NEAR(r.transfer_rate, want_rate, 1e-9 * want_rate);
}

TEST(DieDiagnostics, ImpactsAreFirstArrivalsAtTheSteppedFloor) {
  const Species sp = powder();
  DieDiagnostics d(spec(), {sp.mass()}, {sp.diameter()});
  const double r = 0.5 * sp.diameter(), band = 0.25 * sp.diameter();
  Particles p;
  // Type 1: shallow floor (z = 7 mm) left of x = 42 mm, deep floor (z = 2 mm) right of it.
  p.add(0, 0, sp, {39e-3, 20e-3, 7e-3 + r + band + 1e-4}, {0, 0, -0.3});  // above the shallow floor
  p.add(1, 0, sp, {45e-3, 20e-3, 7e-3 + r}, {0, 0, -0.2});                // at shallow height but over the deep part
  d.observe(0.0, p);
  EXPECT_TRUE(d.impacts().empty());
  p.x[0].z = 7e-3 + r + 0.5 * band;  // now within the band of the shallow floor
  p.x[1].z = 2e-3 + r + 0.1 * band, p.v[1].z = -0.4;
  d.observe(1e-4, p);
  d.observe(2e-4, p);  // the same parcels again: counted once
  ASSERT_EQ(d.impacts().size(), 2u);
  auto front = d.front_impact();
  ASSERT_TRUE(front.has_value());
  std::printf("[ diagnostics ] front at t = %.1e s, mean impact speed %.3f m/s (want 0.350)\n", front->first,
              front->second);
  EXPECT_DOUBLE_EQ(front->first, 1e-4);
  EXPECT_NEAR(front->second, 0.35, 1e-12);
}

// A parcel of l = 1 (d = 125 um: band 31 um) falls at 0.33 m/s onto the shallow floor and
// rebounds with e = 0.9, seen only every 0.2 ms (66 um of travel per look, more than the
// band). With the look ahead (horizon = the interval between looks) the recorded speed is
// the approach speed and the time the instant the parcel enters the band, both exact for
// this constant-speed fall; seen without it, the parcel is first caught after the bounce.
TEST(DieDiagnostics, ImpactSpeedIsTheApproachSpeedWhenLooksAreSparse) {
  const Species sp{"p", 125e-6, 1, 1500};
  const double r = 0.5 * sp.diameter(), band = 0.25 * sp.diameter(), v0 = 0.33, dt = 2e-4;
  const double floor = 7e-3, z0 = floor + r + 0.45e-3;  // lowest point 0.45 mm above the floor
  const double t_band = (z0 - r - floor - band) / v0, t_hit = (z0 - r - floor) / v0;
  // Ballistic without gravity: down at v0 until contact, then up at 0.9 v0 (the collision,
  // 1.2e-5 s, is short against the look interval and taken as instantaneous).
  auto state = [&](double t) {
    if (t < t_hit) return std::make_pair(z0 - v0 * t, -v0);
    return std::make_pair(floor + r + 0.9 * v0 * (t - t_hit), 0.9 * v0);
  };
  auto run = [&](double horizon) {
    DieDiagnostics d(spec(), {sp.mass()}, {sp.diameter()});
    Particles p;
    p.add(0, 0, sp, {39e-3, 20e-3, z0}, {0, 0, -v0});
    for (int n = 0; n * dt < 4e-3; ++n) {
      const auto [z, vz] = state(n * dt);
      p.x[0].z = z, p.v[0].z = vz;
      d.observe(n * dt, p, horizon);
    }
    return d.impacts();
  };
  const auto ahead = run(dt), seen = run(0.0);
  ASSERT_EQ(ahead.size(), 1u);
  ASSERT_EQ(seen.size(), 1u);
  std::printf("[ diagnostics ] sparse looks (%.0f um per look, band %.0f um): look ahead: t %.6e s (want %.6e), "
              "speed %.4f m/s (want %.4f); as seen: t %.1e s, speed %+.4f m/s (after the bounce)\n",
              1e6 * v0 * dt, 1e6 * band, ahead[0].t, t_band, ahead[0].speed_down, v0, seen[0].t, seen[0].speed_down);
  EXPECT_NEAR(ahead[0].t, t_band, 1e-12);
  EXPECT_NEAR(ahead[0].speed_down, v0, 1e-12);
  EXPECT_LT(seen[0].speed_down, 0);  // what the look ahead is for: this parcel was seen moving up
}

TEST(DieDiagnostics, GaugePressureOfStillAirIsZero) {
  const Species sp = powder();
  DieDiagnostics d(spec(), {sp.mass()}, {sp.diameter()});
  fluid::MacGrid g;
  g.nx = 140, g.ny = 70, g.nz = 50, g.dx = 0.6e-3;
  fluid::FluidState air = fluid::make_fluid_state(g);
  fluid::FluidParams fp;
  fp.rho = 1.0, fp.gravity = {0, 0, -9.81};
  fp.bc[5].type = fluid::BcType::Open, fp.bc[5].pressure = 100;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) air.p(i, j, k) = 100 + 9.81 * (30e-3 - g.cell_centre(i, j, k).z) + 2.5;
  Particles p;
  auto r = d.row(0, p, &air, &fp);
  std::printf("[ diagnostics ] gauge pressure in A: %.3e Pa (want 2.5: hydrostatic removed)\n", r.pressure[0]);
  EXPECT_NEAR(r.pressure[0], 2.5, 1e-9);
}

// The cell average takes exactly the cells whose centres lie in the box: with p = i + 1000 j
// + 1e6 k (no gravity) the mean identifies the index set. Box A spans x 40.0..41.2 mm,
// y 20.0..21.2 mm, z 8.0..9.2 mm: centres (i + 0.5) 0.6 mm inside: (39.9 mm, i = 66, is
// outside, 40.5 and 41.1 inside: i = 67, 68), j = 33, 34, k = 13, 14 -> mean 67.5 + 33500 + 13.5e6.
TEST(DieDiagnostics, PressureCellAveragesTheCellsWhoseCentresLieInTheBox) {
  const Species sp = powder();
  DieDiagnostics d(spec(), {sp.mass()}, {sp.diameter()});
  fluid::MacGrid g;
  g.nx = 140, g.ny = 70, g.nz = 50, g.dx = 0.6e-3;
  fluid::FluidState air = fluid::make_fluid_state(g);
  fluid::FluidParams fp;
  fp.rho = 1.0, fp.gravity = {0, 0, 0};
  fp.bc[5].type = fluid::BcType::Open, fp.bc[5].pressure = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) air.p(i, j, k) = i + 1000.0 * j + 1e6 * k;
  Particles p;
  const double got = d.row(0, p, &air, &fp).pressure[0], want = 67.5 + 33500 + 13.5e6;
  std::printf("[ diagnostics ] index mean in A: %.6f (want %.6f)\n", got, want);
  EXPECT_NEAR(got, want, 1e-6);
}

// metrics.csv of a die-filling run from its diagnostics.csv: peaks over t >= 0 only (the
// settling before the shoe moves is excluded), the final fill mass, NaN rows skipped.
TEST(RunMetrics, DieMetricsTakePeaksOverTheShoeMotionOnly) {
  const std::string path = std::string(CGDEM_BINARY_DIR) + "/tests/die_metrics_diagnostics.csv";
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << "# cgdem test\n"
                         "t,mass_in_die,transfer_rate,impacts,p_A,p_B\n"
                         "-0.01,0,9,0,50,nan\n"    // settling: larger values, ignored
                         "0,0,0,0,1,nan\n"
                         "0.1,1e-4,2e-3,5,3,2\n"
                         "0.2,3e-4,1e-3,9,2,4\n";
  const io::Metrics m = app::die_metrics(path, std::make_pair(0.09, 0.27));
  auto v = [&](const char* n) { return io::metric(m, n, path); };
  std::printf("[ metrics ] rate peak %.3g at %.3g s, p_A peak %.3g at %.3g s, p_B peak %.3g at %.3g s, fill %.3g kg\n",
              v("transfer_rate_peak_kg_s"), v("transfer_rate_peak_time_s"), v("p_A_peak_Pa"), v("p_A_peak_time_s"),
              v("p_B_peak_Pa"), v("p_B_peak_time_s"), v("fill_mass_kg"));
  EXPECT_EQ(v("transfer_rate_peak_kg_s"), 2e-3);
  EXPECT_EQ(v("transfer_rate_peak_time_s"), 0.1);
  EXPECT_EQ(v("p_A_peak_Pa"), 3);
  EXPECT_EQ(v("p_A_peak_time_s"), 0.1);
  EXPECT_DOUBLE_EQ(v("p_A_mean_Pa"), 2);
  EXPECT_EQ(v("p_B_peak_Pa"), 4);
  EXPECT_EQ(v("p_B_peak_time_s"), 0.2);
  EXPECT_DOUBLE_EQ(v("p_B_mean_Pa"), 3);
  EXPECT_EQ(v("fill_mass_kg"), 3e-4);
  EXPECT_EQ(v("front_time_s"), 0.09);
  EXPECT_EQ(v("mean_impact_velocity_m_s"), 0.27);
}
