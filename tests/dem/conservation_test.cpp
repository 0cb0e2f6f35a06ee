// Conservation checks on a free cluster of colliding parcels (no gravity, no walls):
//  * total momentum is conserved to round-off (pair forces are exactly antisymmetric);
//  * with e = 1 and mu = 0 the total energy (kinetic + elastic) is conserved, with an
//    error that shrinks with dt (velocity Verlet: second order);
//  * the same run on 1 and 2 threads gives bit-identical states.
#include <gtest/gtest.h>
#include <omp.h>

#include <random>

#include "dem_test_util.hpp"

namespace cgdem {
namespace {

// A 8x8x8 lattice of parcels with small gaps and random velocities: many collisions.
std::unique_ptr<DemSolver> cluster(double dt, double e, double mu, double l = 2.0) {
  Species s = test::powder(l);
  MaterialParams m;
  m.restitution = e;
  m.friction = mu;
  auto dem = std::make_unique<DemSolver>(std::vector<Species>{s}, m, test::no_gravity(dt), geometry::Scene{});
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nd(0.0, 0.2);
  const double a = 1.02 * s.diameter();
  int id = 0;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        dem->particles().add(id++, 0, s, {i * a, j * a, k * a}, {nd(rng), nd(rng), nd(rng)},
                             {nd(rng) * 100, nd(rng) * 100, nd(rng) * 100});
  return dem;
}

double total_energy(const DemSolver& d) {
  EnergyBudget b = d.energy();
  return b.kinetic_translational + b.kinetic_rotational + b.elastic;
}

TEST(Conservation, MomentumToRoundOff) {
  auto dem = cluster(1e-7, 0.9, 0.3);
  EnergyBudget b0 = dem->energy();
  double scale = 0;
  for (size_t i = 0; i < dem->particles().size(); ++i)
    scale += norm(dem->particles().v[i]) / dem->particles().inv_mass[i];
  long contacts_seen = 0;
  for (int s = 0; s < 2000; ++s) {
    dem->step();
    if (s % 500 == 0) contacts_seen += dem->contact_count();
  }
  EnergyBudget b1 = dem->energy();
  const double err = norm(b1.momentum - b0.momentum) / scale;
  std::printf("[ momentum ] |dP| / sum|m v| = %.3e after 2000 steps (%ld contacts sampled), tol 1e-13\n", err,
              contacts_seen);
  EXPECT_GT(contacts_seen, 100);
  EXPECT_LT(err, 1e-13);
}

TEST(Conservation, ElasticFrictionlessEnergyConvergesWithDt) {
  double errs[2];
  const double dts[2] = {4e-7, 2e-7};
  for (int k = 0; k < 2; ++k) {
    auto dem = cluster(dts[k], 1.0, 0.0);
    const double e0 = total_energy(*dem);
    double worst = 0;
    const long steps = std::lround(6e-4 / dts[k]);
    for (long s = 0; s < steps; ++s) {
      dem->step();
      if (s % 50 == 0) worst = std::max(worst, std::fabs(total_energy(*dem) - e0) / e0);
    }
    errs[k] = worst;
    std::printf("[ energy e=1 mu=0 ] dt=%.1e: max |dE|/E0 = %.3e over %ld steps\n", dts[k], worst, steps);
  }
  std::printf("[ energy e=1 mu=0 ] ratio %.2f (second order -> ~4; required > 2.5), tol at dt=2e-7: 1e-3\n",
              errs[0] / errs[1]);
  EXPECT_LT(errs[1], 1e-3);
  EXPECT_GT(errs[0] / errs[1], 2.5);
}

TEST(Conservation, OneAndTwoThreadsBitIdentical) {
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    auto dem = cluster(1e-7, 0.9, 0.3, 1.0);
    for (int s = 0; s < 2000; ++s) dem->step();
    return dem;
  };
  auto a = run(1), b = run(2);
  omp_set_num_threads(omp_get_num_procs());
  size_t differ = 0;
  for (size_t i = 0; i < a->particles().size(); ++i)
    if (!(a->particles().x[i] == b->particles().x[i]) || !(a->particles().v[i] == b->particles().v[i]) ||
        !(a->particles().omega[i] == b->particles().omega[i]))
      ++differ;
  EnergyBudget ea = a->energy(), eb = b->energy();
  std::printf("[ threads ] particles differing between 1 and 2 threads: %zu of %zu; dissipated %.17g vs %.17g J\n",
              differ, a->particles().size(), ea.dissipated_damping, eb.dissipated_damping);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(ea.dissipated_damping, eb.dissipated_damping);
  EXPECT_EQ(ea.dissipated_friction, eb.dissipated_friction);
}

}  // namespace
}  // namespace cgdem
