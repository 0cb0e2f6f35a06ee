// Budgets per unit mass and their comparison (scaling/budgets.hpp) on synthetic energy.csv
// files with analytic columns. Reference run: M = 2 kg, e_pot = -t, e_trans = t/2 (J/kg), on
// t = 0, 0.01 .. 1 s, so S_E = 1 J/kg; the other run (M = 2 kg) is written on a coarser,
// shifted time base (0.015 s) with e_trans + 0.02 sin(pi t). Its deviation must read
// D = 0.02 (linear resampling of the sine: error <= h^2/8 * 0.02 pi^2 = 5.6e-6; tol 1e-5),
// the closure of a budget that holds is 0, and a run whose balance drifts by 0.03 t J/kg
// reads a closure of 0.03.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "scaling/budgets.hpp"

namespace cgdem::scaling {
namespace {

namespace fs = std::filesystem;

std::string write_energy(const std::string& name, double dt, double bump, double drift, bool with_orig) {
  const fs::path dir = fs::path(CGDEM_BINARY_DIR) / "scaling_test_out";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream f(p);
  const double M = 2.0;
  f << "# synthetic\nt,E_kin_trans,E_kin_rot," << (with_orig ? "E_kin_rot_orig," : "")
    << "E_pot,E_elastic,E_diss_damping,E_diss_friction,W_walls,W_air,E_balance,px,py,pz,mass,particles,removed,"
       "inside_walls\n";
  for (int i = 0;; ++i) {
    const double t = std::min(1.0, i * dt);
    const double e_trans = 0.5 * t + bump * std::sin(std::numbers::pi * t), e_rot = 0.01 * t, e_pot = 5.0 - t;
    const double diss = t - e_trans - e_rot + drift * t;  // keeps the balance at 5 + drift t
    f << t << "," << M * e_trans << "," << M * e_rot << ",";
    if (with_orig) f << M * e_rot / 4 << ",";
    f << M * e_pot << ",0," << M * diss << ",0,0,0," << M * (e_trans + e_rot + e_pot + diss) << ","
      << M * 0.3 * t << ",0," << -M * 0.1 * t << "," << M << ",100,0,0\n";
    if (t >= 1.0) break;
  }
  return p.string();
}

TEST(ScalingBudget, DeviationOfAKnownPerturbation) {
  const Budget a = read_budget(write_energy("ref.csv", 0.01, 0, 0, true), "l=1", 1);
  const Budget b = read_budget(write_energy("other.csv", 0.015, 0.02, 0, true), "l=2", 2);
  const Budget c = read_budget(write_energy("drift.csv", 0.01, 0, 0.03, false), "l=3", 3);
  EXPECT_DOUBLE_EQ(a.mass, 2.0);
  EXPECT_EQ(a.particles, 100);
  const BudgetScales s = budget_scales(a);
  std::printf("S_E = %.15g J/kg (want 1), velocity scale %.15g m/s (want sqrt 2)\n", s.energy, s.velocity);
  EXPECT_NEAR(s.energy, 1.0, 1e-12);
  EXPECT_NEAR(s.velocity, std::sqrt(2.0), 1e-12);
  const auto cmp = compare_budgets({a, b, c}, 0, s);
  ASSERT_EQ(cmp.size(), 3u);
  const double D = cmp[1].max_dev.at("e_trans");
  std::printf("D(e_trans) = %.8f (want 0.02): error %.2e (tol 1e-5) at t = %g s (want 0.5)\n", D,
              std::fabs(D - 0.02), cmp[1].t_max_dev.at("e_trans"));
  EXPECT_NEAR(D, 0.02, 1e-5);
  EXPECT_NEAR(cmp[1].t_max_dev.at("e_trans"), 0.5, 0.011);
  EXPECT_LT(cmp[1].max_dev.at("e_pot"), 1e-12);
  EXPECT_LT(cmp[1].max_dev.at("v_x"), 1e-12);
  EXPECT_NEAR(cmp[0].max_dev.at("closure"), 0.0, 1e-12);
  std::printf("closure of the drifting run %.12f (want 0.03)\n", cmp[2].max_dev.at("closure"));
  EXPECT_NEAR(cmp[2].max_dev.at("closure"), 0.03, 1e-9);
  // Without E_kin_rot_orig, e_rot / l^2 is used and flagged.
  EXPECT_TRUE(c.rot_orig_derived);
  EXPECT_NEAR(c.q.at("e_rot_orig").back(), 0.01 / 9, 1e-12);
  EXPECT_NEAR(cmp[1].mean_ratio.at("e_rot_orig"), 1.0, 1e-9);
  EXPECT_NEAR(b.q.at("e_rot_orig").back() * 4, b.q.at("e_rot").back(), 1e-12);
}

TEST(ScalingBudget, MissingColumnIsNamed) {
  const fs::path p = fs::path(CGDEM_BINARY_DIR) / "scaling_test_out" / "bad.csv";
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "t,E_kin_trans\n0,1\n";
  try {
    read_budget(p.string(), "x", 1);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'mass'"), std::string::npos) << e.what();
  }
}

// A run made without the energy accounts (nan in its dissipation columns) is refused by name.
TEST(ScalingBudget, RunWithoutTheAccountsIsRefused) {
  const fs::path p = fs::path(CGDEM_BINARY_DIR) / "scaling_test_out" / "no_accounts.csv";
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "t,E_kin_trans,E_kin_rot,E_pot,E_elastic,E_diss_damping,E_diss_friction,W_walls,E_balance,px,py,"
                      "pz,mass\n0,1,0,1,0,nan,nan,nan,nan,0,0,0,1\n0.1,1,0,1,0,nan,nan,nan,nan,0,0,0,1\n";
  try {
    read_budget(p.string(), "x", 1);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    std::printf("[ scaling ] %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("output.energy_accounts = false"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cgdem::scaling
