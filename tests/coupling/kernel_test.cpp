// The particle-grid kernel: exact conservation of deposited volume (also next to the
// domain sides and on periodic axes), adjointness of deposit and interpolation, linear
// fields interpolated exactly, and smoothness of the void fraction of a moving parcel at
// the die-filling resolution dx/d = 1.6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "coupling/exchange.hpp"
#include "coupling/kernel.hpp"
#include "fluid/ibm.hpp"
#include "geometry/shape.hpp"

using namespace cgdem;
using namespace cgdem::coupling;

namespace {

fluid::MacGrid grid(int nx, int ny, int nz, double dx) {
  fluid::MacGrid g;
  g.nx = nx, g.ny = ny, g.nz = nz, g.dx = dx;
  g.origin = {0, 0, 0};
  return g;
}

double field_sum(const fluid::Field& f) {
  double s = 0;
  for (int k = 0; k < f.nk(); ++k)
    for (int j = 0; j < f.nj(); ++j)
      for (int i = 0; i < f.ni(); ++i) s += f(i, j, k);
  return s;
}

}  // namespace

TEST(Kernel, DepositConservesEverywhere) {
  const auto g = grid(8, 6, 5, 1e-3);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0, 8e-3), uy(0, 6e-3), uz(0, 5e-3);
  double worst = 0;
  for (auto periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true}}) {
    Lattice L = cell_lattice(g, periodic);
    fluid::Field f = fluid::make_cell_field(g);
    double total = 0;
    for (int n = 0; n < 2000; ++n) {
      const double v = 1 + n % 7;
      deposit(flatten(tsc_stencil(L, {ux(rng), uy(rng), uz(rng)}), f), v, f);
      total += v;
    }
    worst = std::max(worst, std::fabs(field_sum(f) - total) / total);
    for (int d = 0; d < 3; ++d) {  // face lattices
      Lattice F = face_lattice(g, d, periodic);
      fluid::Field ff = fluid::make_face_field(g, d);
      deposit(flatten(tsc_stencil(F, {1e-5, 5.99e-3, 2.5e-3}), ff), 1.0, ff);  // next to two sides
      double s = field_sum(ff);
      worst = std::max(worst, std::fabs(s - 1.0));
    }
  }
  std::printf("[ kernel ] relative conservation error of deposits: %.2e (tol 1e-14)\n", worst);
  EXPECT_LT(worst, 1e-14);
}

TEST(Kernel, InterpolatesLinearFieldsExactlyAwayFromSides) {
  const auto g = grid(10, 10, 10, 1e-3);
  Lattice L = cell_lattice(g, {false, false, false});
  fluid::Field f = fluid::make_cell_field(g);
  auto lin = [](const Vec3& x) { return 3 + 200 * x.x - 100 * x.y + 50 * x.z; };
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) f(i, j, k) = lin(g.cell_centre(i, j, k));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(2e-3, 8e-3);
  double worst = 0;
  for (int n = 0; n < 500; ++n) {
    Vec3 x{u(rng), u(rng), u(rng)};
    worst = std::max(worst, std::fabs(interpolate(flatten(tsc_stencil(L, x), f), f) - lin(x)));
  }
  std::printf("[ kernel ] max error interpolating a linear field: %.2e (tol 1e-12)\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(Kernel, DepositIsTheAdjointOfInterpolation) {
  // sum_nodes deposit(x, c) * u(node) == c * interpolate(x, u): the air receives exactly
  // the drag the parcels feel when both use the same velocity field.
  const auto g = grid(6, 7, 8, 1e-3);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 6e-3), val(-1, 1);
  double worst = 0;
  for (int d = 0; d < 3; ++d) {
    Lattice F = face_lattice(g, d, {false, true, false});
    fluid::Field uf = fluid::make_face_field(g, d), dep = fluid::make_face_field(g, d);
    for (int k = 0; k < uf.nk(); ++k)
      for (int j = 0; j < uf.nj(); ++j)
        for (int i = 0; i < uf.ni(); ++i) uf(i, j, k) = val(rng);
    double lhs = 0, rhs = 0;
    for (int n = 0; n < 100; ++n) {
      Vec3 x{u(rng), u(rng), u(rng)};
      const double c = 1 + n;
      Weights s = flatten(tsc_stencil(F, x), dep);
      deposit(s, c, dep);
      rhs += c * interpolate(s, uf);
    }
    auto e = F.n;
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) lhs += dep(i, j, k) * uf(i, j, k);
    worst = std::max(worst, std::fabs(lhs - rhs) / std::fabs(rhs));
  }
  std::printf("[ kernel ] |<deposit, u> - <c, interpolate(u)>| / |.|: %.2e (tol 1e-13)\n", worst);
  EXPECT_LT(worst, 1e-13);
}

TEST(Kernel, VoidFractionOfAMovingParcelIsSmoothAtDieFillingResolution) {
  // An l = 3 parcel (d = 375 um) crossing cells of 0.6 mm (dx/d = 1.6): eps of the cell it
  // starts in must change by a small amount per small step (C1 kernel; centroid binning
  // would jump by V/dx^3 = 0.128 at once).
  const auto g = grid(6, 6, 6, 0.6e-3);
  std::vector<Species> sp{{"p", 125e-6, 3, 1500}};
  fluid::FluidBoundary bc = fluid::uniform_boundary(fluid::BcType::Wall);
  Exchange ex(g, sp, {DragLaw::ErgunWenYu, {}, 0.2, bc});
  Particles p;
  p.add(0, 0, sp[0], {1.5e-3, 1.8e-3, 1.8e-3});
  fluid::Field eps = fluid::make_cell_field(g, 1.0);
  double prev = -1, max_jump = 0;
  const double step = 0.01e-3;
  for (int n = 0; n <= 120; ++n) {
    p.x[0].x = 1.5e-3 + n * step;
    auto st = ex.void_fraction(p, eps);
    EXPECT_NEAR(st.grid_volume, st.parcel_volume, 1e-15 * st.parcel_volume);
    if (prev >= 0) max_jump = std::max(max_jump, std::fabs(eps(2, 3, 3) - prev));
    prev = eps(2, 3, 3);
  }
  const double binning_jump = sp[0].volume() / std::pow(0.6e-3, 3);
  std::printf("[ kernel ] largest change of eps per 10 um step: %.2e (centroid binning: %.3f; tol 1e-2)\n", max_jump,
              binning_jump);
  EXPECT_LT(max_jump, 1e-2);
}

TEST(Kernel, ParcelsOnAFloorPutNoVolumeIntoTheWall) {
  // A layer of l = 3 parcels resting on a floor at z = 1.3 mm (not on a grid line) of a
  // 0.6 mm grid: with the wall-masked weights no solid volume lands in cells inside the
  // floor (alpha = 1), the total is still exact, and the cells just above the floor carry
  // what the plain kernel would have pushed into the floor.
  const auto g = grid(8, 8, 8, 0.6e-3);
  std::vector<Species> sp{{"p", 125e-6, 3, 1500}};
  geometry::Scene scene;
  int b = scene.add_body("floor", geometry::Motion{});
  scene.add_part(b, "floor", geometry::make_half_space({0, 0, 1.3e-3}, {0, 0, 1}));
  fluid::IbmFractions walls;
  fluid::update_ibm(g, scene.at(0), 4, walls);
  fluid::FluidBoundary bc = fluid::uniform_boundary(fluid::BcType::Wall);
  Exchange plain(g, sp, {DragLaw::ErgunWenYu, {}, 0.0, bc}), masked_ex = plain;
  masked_ex.set_walls(&walls);
  Particles p;
  const double r = 0.5 * sp[0].diameter();
  int64_t id = 0;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i) p.add(id++, 0, sp[0], {(i + 0.5) * 0.4e-3, (j + 0.5) * 0.4e-3, 1.3e-3 + r});
  fluid::Field e_plain = fluid::make_cell_field(g, 1.0), e_masked = fluid::make_cell_field(g, 1.0);
  auto s_plain = plain.void_fraction(p, e_plain);
  auto s_masked = masked_ex.void_fraction(p, e_masked);
  double in_wall_plain = 0, in_wall_masked = 0;
  const double vc = std::pow(0.6e-3, 3);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        if (walls.alpha_cell(i, j, k) >= 1.0) {
          in_wall_plain += (1 - e_plain(i, j, k)) * vc;
          in_wall_masked += (1 - e_masked(i, j, k)) * vc;
        }
  std::printf("[ kernel ] floor: share of parcel volume inside the wall: plain %.3f, masked %.1e (tol 1e-14); "
              "conservation error %.1e\n",
              in_wall_plain / s_plain.parcel_volume, in_wall_masked / s_masked.parcel_volume,
              std::fabs(s_masked.grid_volume - s_masked.parcel_volume) / s_masked.parcel_volume);
  EXPECT_GT(in_wall_plain, 0.05 * s_plain.parcel_volume);  // the problem the mask solves is real
  EXPECT_LT(in_wall_masked, 1e-14 * s_masked.parcel_volume);
  EXPECT_NEAR(s_masked.grid_volume, s_masked.parcel_volume, 1e-14 * s_masked.parcel_volume);
}
