// Open sides of the air and gravity ([air.boundary], app/air_case.cpp): air at rest between
// an open top and an open bottom must stay at rest. The closed form is u = 0 and the
// hydrostatic p(z) = p_open + rho g (H - z), which needs the bottom side at p_open + rho g H;
// with the one pressure on both sides (the reader before 5 December 2026) the air column is
// pushed down by rho g H and accelerates. Also: an open side along which gravity acts is
// refused with the key named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "fluid/fluid_state.hpp"
#include "geometry/scene.hpp"
#include "solvers/fluid/fluid_solver.hpp"

using namespace cgdem;

namespace {

// A 2 x 2 x 20 mm column of air (1 mm cells), no parcels in it; `boundary` is the
// [air.boundary] table's body.
std::string column_case(const std::string& boundary) {
  return "[particles]\nseed = 1\n"
         "[[particles.species]]\nname = \"p\"\nd_original = 125e-6\nratio = 1\ndensity = 1500.0\n"
         "[[particles.insert]]\nspecies = \"p\"\ncount = 1\nmin = [0.5e-3, 0.5e-3, 18e-3]\nmax = [1.5e-3, 1.5e-3, "
         "19e-3]\n"
         "[contact]\nstiffness = 50.0\nrestitution = 0.9\nfriction = 0.3\n"
         "[domain]\nmin = [0.0, 0.0, 0.0]\nmax = [2e-3, 2e-3, 20e-3]\n"
         "[time]\nend = 1e-3\ndt = 1e-6\n"
         "[output]\ndir = \"out\"\n"
         "[air]\ndx = 1e-3\ndensity = 1.2\n"
         "[air.boundary]\nopen_pressure = 5.0\n" +
         boundary;
}

struct Column {
  double w_max = 0;   // largest |vertical air velocity| after the run [m/s]
  double p_err = 0;   // largest |p - (p_open + rho g (H - z))| over the cells [Pa]
  double p_bottom = 0;
};

// Runs the column for 200 fluid steps of 1e-4 s from rest; `same_pressure` puts the bottom
// side at the top's pressure (the old reading).
Column run_column(bool same_pressure) {
  Config cfg = Config::from_string(column_case("z_min = \"open\"\n"), "column.toml");
  app::DemCase dc = app::read_dem_case(cfg);
  app::AirCase a = app::read_air_case(cfg, dc.dem);
  Column c;
  c.p_bottom = a.fluid.bc[4].pressure;
  if (same_pressure) a.fluid.bc[4].pressure = a.fluid.bc[5].pressure;
  a.fluid.pressure.rel_tol = 1e-12;
  fluid::FluidSolver solver(a.grid, a.fluid);
  fluid::FluidState s = fluid::make_fluid_state(a.grid);
  geometry::Scene scene;
  const double dt = 1e-4, H = 20e-3, g = 9.81;
  for (int q = 0; q < 200; ++q) solver.advance(s, scene.at(s.t + dt), {}, dt);
  for (int k = 0; k < s.w.nk(); ++k)
    for (int j = 0; j < s.w.nj(); ++j)
      for (int i = 0; i < s.w.ni(); ++i) c.w_max = std::max(c.w_max, std::fabs(s.w(i, j, k)));
  for (int k = 0; k < a.grid.nz; ++k) {
    const double z = (k + 0.5) * a.grid.dx;
    for (int j = 0; j < a.grid.ny; ++j)
      for (int i = 0; i < a.grid.nx; ++i)
        c.p_err = std::max(c.p_err, std::fabs(s.p(i, j, k) - (5.0 + 1.2 * g * (H - z))));
  }
  return c;
}

}  // namespace

TEST(StillAir, StaysAtRestBetweenAnOpenTopAndBottom) {
  const Column now = run_column(false), old = run_column(true);
  const double rho_g_h = 1.2 * 9.81 * 20e-3;
  std::printf("[ error ] still air, open top and bottom: bottom side at %.6f Pa (closed form %.6f); after 0.02 s "
              "max |w| %.2e m/s (tol 1e-9), max |p - hydrostatic| %.2e Pa (tol 1e-9); both sides at one pressure: "
              "max |w| %.2e m/s\n",
              now.p_bottom, 5.0 + rho_g_h, now.w_max, now.p_err, old.w_max);
  EXPECT_NEAR(now.p_bottom, 5.0 + rho_g_h, 1e-12);
  EXPECT_LT(now.w_max, 1e-9);
  EXPECT_LT(now.p_err, 1e-9);
  EXPECT_GT(old.w_max, 1e-3);  // the defect this guards against is visible at this size
}

TEST(StillAir, AnOpenSideAlongGravityIsRefused) {
  Config cfg = Config::from_string(column_case("x_min = \"open\"\n"), "column.toml");
  app::DemCase dc = app::read_dem_case(cfg);
  try {
    app::read_air_case(cfg, dc.dem);
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    std::printf("[ message ] %s\n", m.c_str());
    EXPECT_NE(m.find("air.boundary.x_min"), std::string::npos) << m;
    EXPECT_NE(m.find("normal to gravity"), std::string::npos) << m;
  }
}
