// Conservation checks on a free cluster of colliding parcels (no gravity, no walls):
//  * total momentum is conserved to round-off (pair forces are exactly antisymmetric);
//  * with e = 1 and mu = 0 the total energy (kinetic + elastic) is conserved, with an
//    error that shrinks with dt (velocity Verlet: second order);
//  * the same run on 1, 2, 3 and 4 threads, and with the team changing during the run,
//    gives bit-identical states.
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <map>
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

// 2, 3 and 4 threads against 1 (the name is older than the 3 and 4): the force pass gives
// each thread a chunk of its 4 blocks of owners, so which partners one thread sums directly
// and which go through the stored shares differs with the team size.
// threads 0: the team changes every 70 steps (2, 3, 1, 4, ...), mostly between list builds:
// each change hands the partners near the chunk boundaries to the stored shares anew, whose
// old contents must not leak into a sum.
TEST(Conservation, OneAndTwoThreadsBitIdentical) {
  auto run = [](int threads) {
    omp_set_num_threads(threads > 0 ? threads : 2);
    auto dem = cluster(1e-7, 0.9, 0.3, 1.0);
    for (int s = 0; s < 2000; ++s) {
      if (threads == 0 && s % 70 == 0) omp_set_num_threads(std::array<int, 4>{2, 3, 1, 4}[s / 70 % 4]);
      dem->step();
    }
    return dem;
  };
  auto a = run(1);
  for (const int threads : {2, 3, 4, 0}) {
    auto b = run(threads);
    size_t differ = 0;
    for (size_t i = 0; i < a->particles().size(); ++i)
      if (!(a->particles().x[i] == b->particles().x[i]) || !(a->particles().v[i] == b->particles().v[i]) ||
          !(a->particles().omega[i] == b->particles().omega[i]))
        ++differ;
    EnergyBudget ea = a->energy(), eb = b->energy();
    std::printf("[ threads ] particles differing between 1 and %d threads (0: changing): %zu of %zu; dissipated %.17g "
                "vs %.17g J\n",
                threads, differ, a->particles().size(), ea.dissipated_damping, eb.dissipated_damping);
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(ea.dissipated_damping, eb.dissipated_damping);
    EXPECT_EQ(ea.dissipated_friction, eb.dissipated_friction);
  }
  omp_set_num_threads(omp_get_num_procs());
}

// The force pass skips gathering the radii when every parcel has the same one (the
// screening of the list entries takes r + r from a register). That must be the
// gathered path's bits: the cluster stepped alone (every parcel of one radius) against the
// same cluster beside one parcel of a second species, of 100 instead of 125 um, far above
// it (the radii differ: the screening gathers them and the kernel is the several-species
// one with its parameter table). The far parcel touches nothing and sorts last, and it is
// the smaller one, so the cell size and the skin (set by the largest diameter) stay: the
// cluster's sums keep their order. The test fails when the shortcut's sum of radii is too
// small (1 % smaller: 511 of 512 parcels differ); a larger one only lets through entries
// that the kernel then finds apart, which changes nothing.
TEST(Conservation, UniformRadiusShortcutIsTheGatheredPath) {
  auto run = [](bool far_parcel) {
    auto dem = cluster(1e-7, 0.9, 0.3, 1.0);
    if (!far_parcel) return dem;
    Species small = test::powder(1.0, 100e-6);
    small.name = "small";
    MaterialParams m;  // as cluster()'s
    m.restitution = 0.9;
    m.friction = 0.3;
    auto two = std::make_unique<DemSolver>(std::vector<Species>{dem->species()[0], small}, m, test::no_gravity(1e-7),
                                           geometry::Scene{});
    const Particles& p = dem->particles();
    for (size_t i = 0; i < p.size(); ++i)
      two->particles().add(p.id[i], 0, two->species()[0], p.x[i], p.v[i], p.omega[i]);
    two->particles().add(100000, 1, two->species()[1], {0, 0, 0.05}, {}, {});
    return two;
  };
  auto a = run(false), b = run(true);
  long contacts_seen = 0;
  for (int s = 0; s < 2000; ++s) {
    a->step(), b->step();
    if (s % 100 == 0) contacts_seen += a->contact_count();
  }
  std::map<int64_t, size_t> in_b;
  for (size_t k = 0; k < b->particles().size(); ++k) in_b[b->particles().id[k]] = k;
  const Particles &pa = a->particles(), &pb = b->particles();
  size_t differ = 0;
  for (size_t i = 0; i < pa.size(); ++i) {
    const size_t k = in_b.at(pa.id[i]);
    if (!(pa.x[i] == pb.x[k]) || !(pa.v[i] == pb.v[k]) || !(pa.omega[i] == pb.omega[k])) ++differ;
  }
  const EnergyBudget ea = a->energy(), eb = b->energy();
  std::printf("[ uniform radius ] parcels differing between the shortcut and the gathered path: %zu of %zu after "
              "2000 steps (%ld contacts sampled); dissipated %.17g vs %.17g J\n",
              differ, pa.size(), contacts_seen, ea.dissipated_damping, eb.dissipated_damping);
  EXPECT_EQ(b->particles().size(), pa.size() + 1);
  EXPECT_GT(contacts_seen, 100);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(ea.dissipated_damping, eb.dissipated_damping);
  EXPECT_EQ(ea.dissipated_friction, eb.dissipated_friction);
}

// The cluster with air forces on every parcel: a drag coefficient, an air velocity and an
// external force (the coupling's f_ext), drawn at random; omega too.
void add_air(DemSolver& dem) {
  Particles& p = dem.particles();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (size_t i = 0; i < p.size(); ++i) {
    const double m = 1.0 / p.inv_mass[i];
    p.drag[i] = m * 2000.0 * (1.0 + u(rng));  // relaxation times of 0.25 ms and longer
    p.u_fluid[i] = {u(rng), u(rng), u(rng)};
    p.f_ext[i] = m * 5.0 * Vec3{u(rng), u(rng), u(rng)};
  }
  dem.enable_air_forces(true);
}

// advance(n) fuses the closing half kick of a step with the opening one of the next; the
// result must be that of n calls of step() to the bit, with air (the implicit drag and
// its accounts) and without, on 1 and 2 threads.
TEST(Conservation, AdvanceIsStepsToTheBit) {
  for (const bool air : {false, true})
    for (const int threads : {1, 2}) {
      omp_set_num_threads(threads);
      auto a = cluster(1e-7, 0.9, 0.3, 1.0), b = cluster(1e-7, 0.9, 0.3, 1.0);
      if (air) add_air(*a), add_air(*b);
      for (int s = 0; s < 700; ++s) a->step();
      b->advance(1), b->advance(0), b->advance(250), b->advance(449);
      const Particles &pa = a->particles(), &pb = b->particles();
      size_t differ = 0;
      for (size_t i = 0; i < pa.size(); ++i)
        if (!(pa.x[i] == pb.x[i]) || !(pa.v[i] == pb.v[i]) || !(pa.omega[i] == pb.omega[i]) ||
            !(pa.j_drag[i] == pb.j_drag[i]) || pa.w_fluid[i] != pb.w_fluid[i])
          ++differ;
      std::printf("[ advance ] air %d, %d thread(s): %zu of %zu parcels differ after 700 steps (%ld contacts), "
                  "fluid work %.6e J\n",
                  air, threads, differ, pa.size(), a->contact_count(), a->fluid_work());
      EXPECT_EQ(a->steps(), b->steps());
      EXPECT_EQ(differ, 0u);
      EXPECT_GT(a->contact_count(), 50);
      if (air) EXPECT_GT(std::fabs(a->fluid_work()), 0.0);
    }
  omp_set_num_threads(omp_get_num_procs());
}

// One step of two parcels far apart (no contacts, no gravity): the velocity and the air
// accounts must be those of the header's formulas written out with Vec3 arithmetic, to the
// bit (the kick runs component by component over flat arrays, vectorized).
TEST(Conservation, KickIsTheHeadersFormulaToTheBit) {
  for (const bool air : {false, true}) {
    Species s = test::powder(1.0);
    DemSolver dem({s}, MaterialParams{}, test::no_gravity(1e-6), geometry::Scene{});
    dem.particles().add(0, 0, s, {0, 0, 0}, {0.3, -0.2, 0.1}, {50, -20, 10});
    dem.particles().add(1, 0, s, {0.1, 0, 0}, {-0.1, 0.4, 0.7}, {-5, 2, 1});
    Particles& p = dem.particles();
    p.f_ext[0] = {1e-8, -2e-8, 3e-8}, p.f_ext[1] = {-4e-9, 5e-9, 6e-9};
    if (air) {
      p.drag[0] = 3e-6, p.drag[1] = 1e-5;
      p.u_fluid[0] = {0.01, 0.02, -0.5}, p.u_fluid[1] = {-0.3, 0.2, 0.1};
      dem.enable_air_forces(true);
    }
    const double h = 0.5e-6;
    const Particles p0 = p;
    auto kick = [&](int i, Vec3& v, Vec3& w, Vec3& j_drag, double& w_fluid) {
      const Vec3 F = p0.f_ext[i];  // the force pass: gravity (0) + f_ext + no contacts
      if (air) {
        const double hm = h * p0.inv_mass[i], c = p0.drag[i];
        const Vec3 v0 = v;
        const Vec3 v1 = (1.0 / (1.0 + hm * c)) * (v0 + hm * (F + c * p0.u_fluid[i]));
        const Vec3 j = (h * c) * (p0.u_fluid[i] - v1);
        j_drag += j;
        w_fluid += dot(h * p0.f_ext[i] + j, 0.5 * (v0 + v1));
        v = v1;
      } else {
        v += (h * p0.inv_mass[i]) * F;
      }
      w += (h * p0.inv_inertia[i]) * Vec3{};  // no torque without contacts
    };
    dem.advance(3);
    for (int i = 0; i < 2; ++i) {
      Vec3 v = p0.v[i], w = p0.omega[i], j{}, x = p0.x[i];
      double wf = 0;
      for (int step = 0; step < 3; ++step) {
        kick(i, v, w, j, wf);
        x += 1e-6 * v;
        kick(i, v, w, j, wf);
      }
      std::printf("[ kick ] air %d, parcel %d: v (%.17g, %.17g, %.17g), fluid work %.6e J\n", air, i, v.x, v.y, v.z,
                  wf);
      EXPECT_TRUE(p.v[i] == v);
      EXPECT_TRUE(p.x[i] == x);
      EXPECT_TRUE(p.omega[i] == w);
      EXPECT_TRUE(p.j_drag[i] == j);
      EXPECT_EQ(p.w_fluid[i], wf);
    }
  }
}

}  // namespace
}  // namespace cgdem
