// Dense-bed DEM benchmark (shared/bench/dem_bed/README.md): a settled bed in a box with
// frictional planar walls at x = 0, 0.010 m, y = 0, 0.006 m and a floor at z = 0; rho 1500,
// k 50 N/m, e 0.9, mu 0.3, l = 1, dt 1e-6 s, gravity 9.81 m/s^2. The figure is
// particles x steps / wall seconds of the stepping loop (reading the bed not counted).
#include <fmt/format.h>
#include <omp.h>

#include <ctime>

#include "bench/bench.hpp"
#include "core/timers.hpp"
#include "io/particle_csv.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::bench {

int run_dem_bench(const DemBenchArgs& args) {
  omp_set_num_threads(args.threads);
  io::ParticleTable bed = io::read_particles_csv(args.bed);
  const double d = bed.d.at(0);
  for (double di : bed.d)
    if (di != d) throw Error("bench dem: the bed must be monodisperse");

  geometry::Scene scene;
  int box = scene.add_body("box", geometry::Motion{});
  scene.add_part(box, "x0", geometry::make_half_space({0, 0, 0}, {1, 0, 0}));
  scene.add_part(box, "x1", geometry::make_half_space({0.010, 0, 0}, {-1, 0, 0}));
  scene.add_part(box, "y0", geometry::make_half_space({0, 0, 0}, {0, 1, 0}));
  scene.add_part(box, "y1", geometry::make_half_space({0, 0.006, 0}, {0, -1, 0}));
  scene.add_part(box, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));

  Species s{"bed", d, 1.0, 1500.0};
  MaterialParams m{50.0, 0.9, 0.3, 0.9, 0.3};
  DemParams p;
  p.dt = 1e-6;
  p.gravity = {0, 0, -9.81};
  p.skin = 0.1 * d;  // as the LAMMPS script: neighbor 0.1 d
  p.domain = {{-0.01, -0.01, -0.01}, {0.02, 0.016, 1.0}};
  DemSolver dem({s}, m, p, scene);
  for (size_t i = 0; i < bed.size(); ++i) dem.particles().add(static_cast<int64_t>(i), 0, s, bed.x[i]);

  dem.step();  // first build and forces, not timed
  dem.timers().reset();
  Stopwatch clock;
  const std::clock_t cpu0 = std::clock();
  for (long k = 0; k < args.steps; ++k) dem.step();
  const double wall = clock.seconds();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const double rate = static_cast<double>(bed.size()) * args.steps / wall;
  EnergyBudget e = dem.energy();
  fmt::print("bench dem: {} particles of {:g} m, {} steps, {} thread(s), {:.3f} s\n", bed.size(), d, args.steps,
             args.threads, wall);
  fmt::print("neighbour entries {} ({:.1f} per particle), contacts {}, list builds {}, E_kin {:.4g} J\n",
             dem.pair_entries(), static_cast<double>(dem.pair_entries()) / bed.size(), dem.contact_count(),
             dem.neighbor_builds(), e.kinetic_translational + e.kinetic_rotational);
  // CPU time of the process over the loop: on a shared machine, wall > cpu / threads means
  // the run did not have its cores to itself.
  fmt::print("processor time {:.3f} s ({:.2f} of {} thread(s) busy), particle-steps per processor-second {:.4e}\n",
             cpu, cpu / wall, args.threads, static_cast<double>(bed.size()) * args.steps / cpu);
  fmt::print("{}", dem.timers().table("per-phase time"));
  // To check that a change of the engine left the trajectory alone (compare across builds).
  fmt::print("state: E_kin {:.17g} E_pot {:.17g} dissipated {:.17g} + {:.17g} J\n",
             e.kinetic_translational + e.kinetic_rotational, e.potential, e.dissipated_damping,
             e.dissipated_friction);
  fmt::print("particle-steps/s: {:.4e}\n", rate);
  return 0;
}

}  // namespace cgdem::bench
