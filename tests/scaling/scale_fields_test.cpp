// Gridded solid fraction (scaling/fields.hpp, cloud-in-cell) and pile observables
// (scaling/observables.hpp) against closed forms.
//  * Deposition conserves the solid volume exactly (sum phi dx^3 = sum V_p, 1e-12 relative),
//    with and without a periodic axis; a parcel at a cell centre fills only that cell.
//  * A flat layer of parcels (one layer, diameter d, centres at z = d/2 over x in [0, 21 d))
//    gives the height profile h = d on the covered columns and 0 beyond, the run-out x_95
//    at the 95 % quantile of the centres and the centre of mass at d/2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "scaling/fields.hpp"
#include "scaling/observables.hpp"

namespace cgdem::scaling {
namespace {

TEST(ScalingFields, CloudInCellConservesVolume) {
  for (bool periodic : {false, true}) {
    const Grid g = grid_over({0, 0, 0}, {10e-3, 4e-3, 6e-3}, 1e-3, {false, periodic, false});
    io::ParticleTable t;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(0, 10e-3), uy(0, 4e-3), uz(0, 6e-3), ud(0.2e-3, 0.6e-3);
    double V = 0;
    for (int i = 0; i < 500; ++i) {
      t.x.push_back({ux(rng), uy(rng), uz(rng)});
      t.d.push_back(ud(rng));
      V += std::numbers::pi * std::pow(t.d.back(), 3) / 6;
    }
    const auto phi = solid_fraction(t, g);
    double sum = 0;
    for (double p : phi) sum += p * g.dx * g.dx * g.dx;
    std::printf("periodic y %d: deposited volume / parcel volume - 1 = %.2e (tol 1e-12)\n", periodic, sum / V - 1);
    EXPECT_NEAR(sum / V, 1.0, 1e-12);
  }
  const Grid g = grid_over({0, 0, 0}, {3e-3, 3e-3, 3e-3}, 1e-3, {false, false, false});
  io::ParticleTable one;
  one.x = {{1.5e-3, 1.5e-3, 1.5e-3}};
  one.d = {1e-3};
  const auto phi = solid_fraction(one, g);
  EXPECT_NEAR(phi[1 + 3 * (1 + 3 * 1)], std::numbers::pi / 6, 1e-12);
}

TEST(ScalingFields, FlatLayerProfile) {
  const double d = 1e-3;
  std::vector<Vec3> x;
  std::vector<double> dd;
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 8; ++j) x.push_back({(i + 0.5) * d, (j + 0.5) * d, 0.5 * d}), dd.push_back(d);
  RunObservables o;
  pile_observables(x, dd, {0, 40e-3, 0, 8e-3, 0, 2e-3}, o);
  ASSERT_EQ(o.profile_h.size(), 20u);
  for (int i = 0; i < 11; ++i) EXPECT_NEAR(o.profile_h[i], d, 1e-15) << "column " << i;
  for (int i = 11; i < 20; ++i) EXPECT_EQ(o.profile_h[i], 0.0) << "column " << i;
  std::printf("flat layer: h = %g m (want %g), x95 = %g m (want %g), com z = %g m (want %g)\n", o.profile_h[0], d,
              o.scalars.at("runout_x95_m"), 19.5 * d, o.scalars.at("com_z_m"), 0.5 * d);
  EXPECT_NEAR(o.scalars.at("runout_x95_m"), 19.5 * d, 1e-15);  // 95 % of 168 = 159.6: the 160th parcel, i = 19
  EXPECT_NEAR(o.scalars.at("com_x_m"), 10.5 * d, 1e-15);
  EXPECT_NEAR(o.scalars.at("com_z_m"), 0.5 * d, 1e-15);
}

}  // namespace
}  // namespace cgdem::scaling
