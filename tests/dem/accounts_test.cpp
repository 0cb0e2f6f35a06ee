// The production switch output.energy_accounts = false (DemParams::accounts): the force pass
// keeps only the tangential springs of the pair histories and books no energy. Every law's
// force depends on the spring alone (contact/laws.hpp), so a run without the accounts must
// move exactly as the same run with them, bit for bit, for every law, with one species or
// several, on one thread or two, and across a checkpoint:
//   * a bed of 300 parcels poured onto a floor (at 0.3 m/s) in a box that is periodic in x and
//     y, with a lid that comes down onto it (wall work), for 15 ms: positions, velocities, spins, the
//     springs of every listed pair and the elastic energy agree to the last bit;
//   * the run without the accounts keeps no other history slot, and its energy budget says
//     NaN (not computed) for the dissipation, the wall work and the balance, while the run
//     with them has dissipated energy (the comparison is not between two idle beds);
//   * stopped halfway, saved and loaded into a new solver, the run without the accounts
//     goes on to the same bits as without the stop.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <string>

#include "contact/laws.hpp"
#include "dem_test_util.hpp"
#include "io/archive.hpp"
#include "particles/insertion.hpp"

namespace cgdem {
namespace {

constexpr double kL = 1.5e-3;

geometry::Scene box_with_lid() {
  geometry::Scene scene;
  const int b = scene.add_body("box", geometry::Motion{});
  scene.add_part(b, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  // The lid starts just above the pour, comes down at 0.6 m/s (catching up with the falling
  // parcels) and stops at z = 3.4 mm at t = 11 ms.
  const int lid = scene.add_body("lid", geometry::Motion({0.0, 11e-3}, {Vec3{0, 0, -0.6}, Vec3{}}));
  scene.add_part(lid, "lid", geometry::make_half_space({0, 0, 10e-3}, {0, 0, -1}));
  return scene;
}

std::unique_ptr<DemSolver> bed(const contact::ContactModel& law, int species, bool accounts) {
  std::vector<Species> s{test::powder(2)};
  if (species == 2) s.push_back({"coarse", 160e-6, 2, 1500.0});
  DemParams p;
  p.dt = 1e-6;
  p.domain = {{0, 0, -1e-3}, {kL, kL, 20e-3}};
  p.periodic = {true, true, false};
  p.accounts = accounts;
  auto dem = std::make_unique<DemSolver>(s, law, p, box_with_lid());
  for (int k = 0; k < species; ++k) {
    const InsertRegion r{{0, 0, 0.3e-3}, {kL, kL, 9.5e-3}, 300 / species, k, Vec3{0, 0, -0.3}};
    insert_random(dem->particles(), dem->species(), r, dem->scene().at(0), 7 + k, k * 300);
  }
  return dem;
}

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

// Number of components that differ between two runs' states (0: the same bits).
long differences(const DemSolver& a, const DemSolver& b) {
  const Particles &p = a.particles(), &q = b.particles();
  long d = !same_bits(p.x, q.x) + !same_bits(p.v, q.v) + !same_bits(p.omega, q.omega);
  d += !same_bits(a.neighbor_list().hist.xi, b.neighbor_list().hist.xi);
  d += !same_bits(a.energy().elastic, b.energy().elastic);
  return d;
}

void run_to(DemSolver& dem, double t) {
  while (dem.time() < t - 0.5 * dem.params().dt) dem.step();
}

struct Case {
  const char* name;
  contact::ContactModel law;
  int species;
};

Case cases(int k) {
  HertzMindlinMaterial hm;
  hm.youngs_modulus = hm.wall_youngs_modulus = 2e7;
  hm.poisson_ratio = hm.wall_poisson_ratio = 0.3;
  hm.restitution = hm.wall_restitution = 0.7;
  hm.friction = hm.wall_friction = 0.3;
  switch (k) {
    case 0: return {"linear, one species", MaterialParams{}, 1};
    case 1: return {"linear, two species", MaterialParams{}, 2};
    default: return {"hertz-mindlin, one species", hm, 1};
  }
}

TEST(EnergyAccounts, OffMovesTheSameToTheLastBit) {
  constexpr double kEnd = 15e-3;
  for (int k = 0; k < 3; ++k) {
    const Case c = cases(k);
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      auto on = bed(c.law, c.species, true), off = bed(c.law, c.species, false);
      run_to(*on, kEnd);
      run_to(*off, kEnd);
      const EnergyBudget e_on = on->energy(), e_off = off->energy();
      const long diff = differences(*on, *off);
      std::printf("[ accounts ] %s, %d thread(s), %zu parcels, %ld DEM steps: %ld of 5 state arrays differ "
                  "(tol 0); with the accounts E_diss = %.3e J, W_walls = %.3e J; without: %g, %g, balance %g; "
                  "history slots kept besides xi: %zu and %zu\n",
                  c.name, threads, on->particles().size(), on->steps(), diff,
                  e_on.dissipated_damping + e_on.dissipated_friction, e_on.work_walls, e_off.dissipated_damping,
                  e_off.work_walls, e_off.balance(), on->neighbor_list().hist.rest.size(),
                  off->neighbor_list().hist.rest.size());
      EXPECT_EQ(diff, 0) << c.name;
      EXPECT_GT(e_on.dissipated_damping, 0) << c.name;
      EXPECT_GT(e_on.dissipated_friction, 0) << c.name;
      EXPECT_GT(std::fabs(e_on.work_walls), 0) << c.name;
      EXPECT_EQ(on->neighbor_list().hist.rest.size(), on->neighbor_list().hist.size());
      EXPECT_TRUE(off->neighbor_list().hist.rest.empty());
      EXPECT_TRUE(std::isnan(e_off.dissipated_damping) && std::isnan(e_off.dissipated_friction) &&
                  std::isnan(e_off.work_walls) && std::isnan(e_off.balance()))
          << c.name;
      EXPECT_TRUE(same_bits(e_on.kinetic_translational, e_off.kinetic_translational)) << c.name;
    }
  }
  omp_set_num_threads(1);
}

TEST(EnergyAccounts, OffRestartsToTheSameBits) {
  const Case c = cases(0);
  auto whole = bed(c.law, c.species, false), first = bed(c.law, c.species, false);
  run_to(*whole, 12e-3);
  run_to(*first, 6e-3);
  io::ArchiveWriter w;
  first->save(w);
  auto second = bed(c.law, c.species, false);
  io::ArchiveReader r(w.bytes(), "in memory");
  second->load(r);
  run_to(*second, 12e-3);
  const long diff = differences(*whole, *second);
  std::printf("[ accounts ] without the accounts, stopped at 6 ms, saved, loaded and run to 12 ms: %ld of 5 state "
              "arrays differ from the run without the stop (tol 0)\n",
              diff);
  EXPECT_EQ(diff, 0);
  EXPECT_TRUE(second->neighbor_list().hist.rest.empty());
}

}  // namespace
}  // namespace cgdem
