// The rotational energy of a parcel and of the l^3 originals it stands for (EnergyBudget,
// solvers/dem/energy.cpp). With I = l^5 I_O (eq. 5) and every original spinning at the
// parcel's w, the originals hold l^3 * I_O w^2 / 2 = (I w^2 / 2) / l^2. Rolling without slip
// at speed v (w = 2 v / d, d = l d_O) the parcel's own energy per unit mass is v^2 / 5 for
// every l while the originals' is v^2 / (5 l^2). Closed forms, tolerance 1e-12 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "solvers/dem/dem_solver.hpp"

namespace cgdem {
namespace {

TEST(ScalingRotation, OriginalsHoldTheParcelsRotationalEnergyOverLSquared) {
  const double d_O = 125e-6, rho = 1500, v = 0.2;
  for (double l : {1.0, 2.0, 3.0, 4.5}) {
    DemParams p;
    p.dt = 1e-6;
    p.gravity = {0, 0, 0};
    p.domain = {{-1, -1, -1}, {1, 1, 1}};
    const Species s{"powder", d_O, l, rho};
    DemSolver dem({s}, MaterialParams{}, p, geometry::Scene{});
    const double d = l * d_O, w = 2 * v / d;  // rolling without slip
    dem.particles().add(0, 0, dem.species()[0], {0, 0, 0}, {v, 0, 0}, {0, w, 0});
    dem.particles().add(1, 0, dem.species()[0], {0.01, 0, 0}, {v, 0, 0}, {0, 0, -w});
    const EnergyBudget e = dem.energy();
    const double m_O = rho * std::numbers::pi * d_O * d_O * d_O / 6, I_O = 0.1 * m_O * d_O * d_O;
    const double want_orig = 2 * l * l * l * 0.5 * I_O * w * w;  // two parcels of l^3 originals
    const double M = e.mass;
    const double err_ratio = std::fabs(e.kinetic_rotational / e.kinetic_rotational_originals / (l * l) - 1);
    const double err_orig = std::fabs(e.kinetic_rotational_originals / want_orig - 1);
    const double err_roll = std::fabs(e.kinetic_rotational / M / (v * v / 5) - 1);
    const double err_roll_orig = std::fabs(e.kinetic_rotational_originals / M / (v * v / (5 * l * l)) - 1);
    std::printf("l = %g: E_rot / E_rot,orig = %.15g (want l^2 = %g); errors: ratio %.1e, originals %.1e, "
                "e_rot = v^2/5 %.1e, e_rot,orig = v^2/(5 l^2) %.1e (tol 1e-12)\n",
                l, e.kinetic_rotational / e.kinetic_rotational_originals, l * l, err_ratio, err_orig, err_roll,
                err_roll_orig);
    EXPECT_LT(err_ratio, 1e-12);
    EXPECT_LT(err_orig, 1e-12);
    EXPECT_LT(err_roll, 1e-12);
    EXPECT_LT(err_roll_orig, 1e-12);
    // The originals' energy is not part of the budget's closure.
    EXPECT_DOUBLE_EQ(e.balance(), e.kinetic_translational + e.kinetic_rotational + e.potential);
  }
}

}  // namespace
}  // namespace cgdem
