// The diagnostics of where the powder and the air go in a die filling, against values
// known by construction: a bubble placed by hand in a bed, the surface of a pile built
// layer by layer, the powder left in the moving shoe, and the air's paths out of the die.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "diagnostics/die_diagnostics.hpp"
#include "fluid/bubbles.hpp"
#include "fluid/fluid_state.hpp"

using namespace cgdem;
using namespace cgdem::diagnostics;

namespace {

DiagnosticsSpec die_spec() {
  DiagnosticsSpec s;
  s.enabled = true;  // die mouth x 37..47 mm, y 6..36 mm; cavity x 22..32 mm at t = 0
  s.die.table_top = 14e-3, s.die.shoe_wall = 3e-3;
  s.cells = {{"A", {40e-3, 20e-3, 8e-3}, {41.2e-3, 21.2e-3, 9.2e-3}}};
  return s;
}

// A 20 x 20 x 30 grid of 1 mm: powder (eps 0.4) below z = 20 mm, air above, open top.
struct Bed {
  fluid::MacGrid g;
  fluid::Field eps, alpha;
  fluid::FluidBoundary bc{};
  Bed() {
    g.nx = 20, g.ny = 20, g.nz = 30, g.dx = 1e-3;
    eps = fluid::make_cell_field(g, 1.0);
    alpha = fluid::make_cell_field(g, 0.0);
    bc[5].type = fluid::BcType::Open;
    for (int k = 0; k < 20; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) eps(i, j, k) = 0.4;
  }
};

}  // namespace

// A sphere of radius 4 mm of pure air (eps = 1) at (10, 10, 10) mm inside the bed: one
// bubble, its volume the cells whose centres lie in the sphere (count n: V = n dx^3, within
// 10 % of 4/3 pi R^3 on this grid), its centroid at the centre by symmetry, its top the
// highest such cell's top face (z = 14 mm). The room's air above the bed is not a bubble.
TEST(Bubbles, AnAirPocketInTheBedIsFoundWithItsVolume) {
  Bed b;
  long n = 0;
  const Vec3 c{10e-3, 10e-3, 10e-3};
  const double R = 4e-3;
  for (int k = 0; k < b.g.nz; ++k)
    for (int j = 0; j < b.g.ny; ++j)
      for (int i = 0; i < b.g.nx; ++i) {
        const Vec3 x = b.g.cell_centre(i, j, k) - c;
        if (x.x * x.x + x.y * x.y + x.z * x.z < R * R) b.eps(i, j, k) = 1.0, ++n;
      }
  const fluid::BubbleCensus census = fluid::find_bubbles(b.g, b.eps, b.alpha, b.bc, 0.9, 1, 10e-3);
  ASSERT_EQ(census.bubbles.size(), 1u);
  EXPECT_NEAR(census.bubbles[0].volume_above, 0.5 * census.bubbles[0].volume, 1e-20);  // upper half (by symmetry)
  const fluid::Bubble& bub = census.bubbles[0];
  const double want = n * 1e-9, sphere = 4.0 / 3.0 * M_PI * R * R * R;
  std::printf("[ bubbles ] volume %.4e m^3 (want %.4e from %ld cells; sphere %.4e, %.1f %%), centroid "
              "(%.3f, %.3f, %.3f) mm, top %.3f mm (want 14)\n",
              bub.volume, want, n, sphere, 100 * (bub.volume / sphere - 1), 1e3 * bub.centroid.x,
              1e3 * bub.centroid.y, 1e3 * bub.centroid.z, 1e3 * bub.z_top);
  EXPECT_NEAR(bub.volume, want, 1e-12 * want);
  EXPECT_NEAR(bub.volume, sphere, 0.1 * sphere);
  EXPECT_NEAR(bub.centroid.x, c.x, 1e-12);
  EXPECT_NEAR(bub.centroid.z, c.z, 1e-12);
  EXPECT_NEAR(bub.z_top, 14e-3, 1e-12);
  EXPECT_EQ(census.sealed_volume, 0.0);

  // The same pocket opened to the bed's surface by a chimney: room air, no bubble.
  for (int k = 13; k < 20; ++k) b.eps(10, 10, k) = 1.0;
  EXPECT_TRUE(fluid::find_bubbles(b.g, b.eps, b.alpha, b.bc, 0.9).bubbles.empty());
}

// Air closed in by walls alone (a sealed box in the air above the bed) is sealed air, not a
// bubble; with a closed top the room's air above the bed becomes one bubble (it touches
// the powder), and with a periodic x axis a pocket split by the x faces is one bubble.
TEST(Bubbles, SealedAirAndPeriodicPockets) {
  Bed b;
  for (int k = 22; k < 28; ++k)  // a wall shell around cells (5..7)^2 x (23..26)
    for (int j = 4; j < 9; ++j)
      for (int i = 4; i < 9; ++i)
        if (i == 4 || i == 8 || j == 4 || j == 8 || k == 22 || k == 27) b.alpha(i, j, k) = 1.0;
  fluid::BubbleCensus census = fluid::find_bubbles(b.g, b.eps, b.alpha, b.bc, 0.9);
  std::printf("[ bubbles ] sealed %.3e m^3 (want 3.6e-08), bubbles %zu (want 0)\n", census.sealed_volume,
              census.bubbles.size());
  EXPECT_TRUE(census.bubbles.empty());
  EXPECT_NEAR(census.sealed_volume, 3 * 3 * 4 * 1e-9, 1e-20);

  Bed closed;
  closed.bc[5].type = fluid::BcType::Wall;
  census = fluid::find_bubbles(closed.g, closed.eps, closed.alpha, closed.bc, 0.9);
  ASSERT_EQ(census.bubbles.size(), 1u);
  EXPECT_NEAR(census.bubbles[0].volume, 20 * 20 * 10 * 1e-9, 1e-18);

  Bed wrap;
  wrap.bc[0].type = wrap.bc[1].type = fluid::BcType::Periodic;
  for (int i : {0, 1, 18, 19}) wrap.eps(i, 10, 5) = 1.0;
  census = fluid::find_bubbles(wrap.g, wrap.eps, wrap.alpha, wrap.bc, 0.9);
  ASSERT_EQ(census.bubbles.size(), 1u);
  EXPECT_EQ(census.bubbles[0].cells, 4);
}

// A pile in the cavity built of a simple cubic lattice of parcels of d = 375 um: column n
// (x bins of 1 mm, two lattice columns each... here the bin holds 2 x 80 columns) stacked
// to n + 2 layers. Surface = top of the highest layer = (n + 2) d (the top layer holds
// 1 / (n + 2) > 2 % of the bin's parcels); solid height = parcels x (pi/6) d^3 / bin area.
// The shoe has moved by 5 mm at t = 0.05 s: the same pile shifted with it reads the same.
TEST(DieDiagnostics, ShoeSurfaceOfAKnownPileAndThePowderLeftInTheShoe) {
  const Species sp{"p", 125e-6, 3, 1500};
  const double d = sp.diameter(), t = 0.05, off = 0.1 * (t - 0.5e-3);  // 1 ms ramp: 5 mm - 0.05 mm
  DieDiagnostics diag(die_spec(), {sp.mass()}, {sp.diameter()});
  EXPECT_NEAR(diag.shoe_offset(t), off, 1e-15);
  Particles p;
  long id = 0;
  const int per_bin_x = 2, ny = 80;  // 2 x 0.375 mm per 1 mm bin, 80 x 0.375 = 30 mm
  for (int b = 0; b < 10; ++b)
    for (int a = 0; a < per_bin_x; ++a)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < b + 2; ++k)
          p.add(id++, 0, sp, {22e-3 + off + b * 1e-3 + (a + 0.5) * d, 6e-3 + (j + 0.5) * d, 14e-3 + (k + 0.5) * d});
  const long in_shoe = id;
  p.add(id++, 0, sp, {40e-3, 20e-3, 10e-3});  // in the die
  p.add(id++, 0, sp, {20e-3, 20e-3, 15e-3});  // on the table behind the shoe
  const std::string rows = diag.surface_rows(t, p);
  double worst_surface = 0, worst_solid = 0;
  int b = 0;
  for (size_t pos = 0; pos < rows.size(); ++b) {
    const size_t end = rows.find('\n', pos);
    double tt, xc, x, solid, surface;
    int bin;
    long n;
    ASSERT_EQ(std::sscanf(rows.substr(pos, end - pos).c_str(), "%lf,%d,%lf,%lf,%lf,%lf,%ld", &tt, &bin, &xc, &x,
                          &solid, &surface, &n),
              7);
    const double want_surface = (b + 2) * d, want_solid = n * M_PI / 6 * d * d * d / (1e-3 * 30e-3);
    EXPECT_EQ(n, per_bin_x * ny * (b + 2));
    EXPECT_NEAR(x, 22e-3 + off + (b + 0.5) * 1e-3, 1e-12);
    worst_surface = std::max(worst_surface, std::abs(surface - want_surface));
    worst_solid = std::max(worst_solid, std::abs(solid - want_solid) / want_solid);
    pos = end + 1;
  }
  EXPECT_EQ(b, 10);
  // The rows carry 9 significant digits: 1e-8 relative is the resolution of the file.
  std::printf("[ diagnostics ] pile surface: largest error %.2e m (tol 1e-12), solid height %.2e relative (tol 1e-8)\n",
              worst_surface, worst_solid);
  EXPECT_LT(worst_surface, 1e-12);
  EXPECT_LT(worst_solid, 1e-8);
  const DiagnosticsRow r = diag.row(t, p, nullptr, nullptr);
  std::printf("[ diagnostics ] mass in the shoe %.6e kg (want %.6e)\n", r.mass_in_shoe, in_shoe * sp.mass());
  EXPECT_NEAR(r.mass_in_shoe, in_shoe * sp.mass(), 1e-12 * r.mass_in_shoe);
  EXPECT_TRUE(std::isnan(r.q_cavity));  // no air
}

// Uniform upward air (eps 1, w = 1 cm/s) on a 1 mm grid aligned with the mouth (x 37..47,
// y 6..36 mm; the plane z = 14 mm is a face plane). At t = 0.10 s (shoe moved 9.95 mm:
// cavity x 31.95..41.95 mm, walls 3 mm) the mouth's faces (centres at .5 mm) count for the
// cavity up to one cell beyond its inner face, x < 42.95 (6 columns), under the leading wall
// to 44.95 (2), open beyond (2): Q = w x area = 1.8e-6, 0.6e-6, 0.6e-6 m^3/s. With eps 0.5
// the fluxes halve.
TEST(DieDiagnostics, AirPathsSplitTheMouthByWhatCoversIt) {
  DieDiagnostics diag(die_spec(), {1e-9}, {375e-6});
  fluid::MacGrid g;
  g.nx = 84, g.ny = 42, g.nz = 30, g.dx = 1e-3;
  fluid::FluidState air = fluid::make_fluid_state(g);
  air.w.fill(0.01);
  PathFlux q = diag.path_fluxes(air, 0.10);
  std::printf("[ diagnostics ] air paths: cavity %.4e, walls %.4e, open %.4e m^3/s (want 1.8e-6, 0.6e-6, 0.6e-6)\n",
              q.cavity, q.walls, q.open);
  EXPECT_NEAR(q.cavity, 1.8e-6, 1e-18);
  EXPECT_NEAR(q.walls, 0.6e-6, 1e-18);
  EXPECT_NEAR(q.open, 0.6e-6, 1e-18);
  air.eps.fill(0.5);
  q = diag.path_fluxes(air, 0.10);
  EXPECT_NEAR(q.cavity + q.walls + q.open, 1.5e-6, 1e-18);
}
