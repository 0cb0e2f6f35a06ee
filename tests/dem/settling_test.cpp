// Settling of the same solid mass at l = 1, 2, 3 (d_O = 125 um) in a box that is periodic
// in x and y (1.5 mm, four l = 3 diameters) on a flat floor:
//  * the energy budget closes: E_kin + E_pot + E_el + dissipated - wall work stays at its
//    initial value to within 1 % of the potential energy released;
//  * coarse-grain consistency: the settled bed's potential energy (centre of mass height)
//    and surface height agree with l = 1 within 4 %, and so does the bulk solid fraction.
//    Periodic sides leave the floor and the free surface as the only places where the
//    parcel size shows (layers about one diameter thick; the bed is 12 l = 3 diameters).
//    The surface is where the horizontally averaged solid fraction falls to half its bulk
//    value (exact sphere-slab volumes), so the parcels' larger roughness does not bias it.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "dem_test_util.hpp"
#include "geometry/shape.hpp"
#include "particles/insertion.hpp"

namespace cgdem {
namespace {

struct Settled {
  double z_cm, height, phi_bulk, budget_error, released, kinetic;
  size_t n;
};

// Volume of a sphere (centre z, radius r) below the plane at height h.
double volume_below(double z, double r, double h) {
  const double c = std::clamp(h - (z - r), 0.0, 2 * r);
  return std::numbers::pi * c * c * (3 * r - c) / 3;
}

// Horizontally averaged solid fraction in slabs of thickness dz, from z = 0.
std::vector<double> solid_profile(const Particles& q, double area, double dz, int nslab) {
  std::vector<double> phi(nslab, 0.0);
  for (size_t i = 0; i < q.size(); ++i)
    for (int k = 0; k < nslab; ++k)
      phi[k] += volume_below(q.x[i].z, q.radius[i], (k + 1) * dz) - volume_below(q.x[i].z, q.radius[i], k * dz);
  for (double& f : phi) f /= area * dz;
  return phi;
}

Settled settle(double l) {
  const double L = 1.5e-3, solid_volume = 225 * test::powder(3).volume();  // 225 parcels at l = 3
  const Species s = test::powder(l);
  geometry::Scene scene;
  const int b = scene.add_body("box", geometry::Motion{});
  scene.add_part(b, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  DemParams p;
  p.dt = 1e-6;
  p.domain = {{0, 0, -1e-3}, {L, L, 20e-3}};
  p.periodic = {true, true, false};
  DemSolver dem({s}, MaterialParams{}, p, scene);
  const InsertRegion r{{0, 0, 0}, {L, L, 12e-3}, std::lround(solid_volume / s.volume()), 0, {}};
  insert_random(dem.particles(), dem.species(), r, scene.at(0), 11, 0);
  const EnergyBudget e0 = dem.energy();
  while (dem.time() < 0.075) dem.step();
  const EnergyBudget e1 = dem.energy();
  const auto& q = dem.particles();
  const double z_cm = e1.potential / (e1.mass * 9.81);
  // Bulk fraction over the middle of the bed, surface where the profile falls to half of it.
  const double dz = 0.02e-3;
  const std::vector<double> phi = solid_profile(q, L * L, dz, static_cast<int>(4 * z_cm / dz));
  double phi_bulk = 0;
  int nb = 0;
  for (size_t k = 0; k < phi.size(); ++k)
    if ((k + 0.5) * dz > 0.5 * z_cm && (k + 0.5) * dz < 1.5 * z_cm) phi_bulk += phi[k], ++nb;
  phi_bulk /= nb;
  double h = 0;
  for (size_t k = phi.size(); k-- > 1;)
    if (phi[k - 1] >= 0.5 * phi_bulk) {  // linear crossing between slab centres k-1 and k
      h = (k - 0.5 + (phi[k - 1] - 0.5 * phi_bulk) / (phi[k - 1] - phi[k])) * dz;
      break;
    }
  const double released = e0.potential - e1.potential;
  return {z_cm, h, phi_bulk, std::fabs(e1.balance() - e0.balance()) / released, released,
          e1.kinetic_translational + e1.kinetic_rotational, q.size()};
}

TEST(Settling, EnergyBudgetClosesAndCoarseGrainingKeepsTheBed) {
  Settled ref{};
  for (double l : {1.0, 2.0, 3.0}) {
    const Settled s = settle(l);
    if (l == 1.0) ref = s;
    const double ez = test::rel_err(s.z_cm, ref.z_cm), eh = test::rel_err(s.height, ref.height),
                 ep = test::rel_err(s.phi_bulk, ref.phi_bulk);
    std::printf("[ settling ] l=%.0f: %zu parcels, z_cm=%.4f mm (vs l=1: %.2e), surface=%.4f mm (vs l=1: %.2e), "
                "bulk fraction %.4f (vs l=1: %.2e), budget error %.2e of %.3e J released, E_kin left %.1e of it; "
                "tol 4e-2, 4e-2, 4e-2, 1e-2\n",
                l, s.n, s.z_cm * 1e3, ez, s.height * 1e3, eh, s.phi_bulk, ep, s.budget_error, s.released,
                s.kinetic / s.released);
    EXPECT_LT(s.budget_error, 1e-2);
    EXPECT_LT(ez, 4e-2);
    EXPECT_LT(eh, 4e-2);
    EXPECT_LT(ep, 4e-2);
    EXPECT_LT(s.kinetic, 1e-3 * s.released);  // settled
  }
}

}  // namespace
}  // namespace cgdem
