// Dense-bed DEM benchmark (shared/bench/dem_bed/README.md): a settled bed in a box with
// frictional planar walls at x = 0, 0.010 m (--box-x), y = 0, 0.006 m (--box-y) and a
// floor at z = 0; rho 1500, k 50 N/m, e 0.9, mu 0.3, l = 1, dt 1e-6 s, gravity 9.81 m/s^2.
// The figure is particles x steps / wall seconds of the stepping loop (reading the bed not
// counted).
#include <fmt/format.h>
#include <omp.h>

#include <ctime>

#include "bench/bench.hpp"
#include "bench/dem/stripped_dem.hpp"
#include "core/timers.hpp"
#include "io/particle_csv.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::bench {

namespace {

// The stripped reference (stripped_dem.hpp) from the engine's state after its first step.
int run_stripped(const DemSolver& dem, const std::vector<Plane>& planes, const DemBenchArgs& args) {
  StrippedDem ref(dem, planes, args.accounts);
  Stopwatch clock;
  for (long k = 0; k < args.steps; ++k) ref.step();
  const double wall = clock.seconds();
  const double rate = static_cast<double>(ref.size()) * args.steps / wall;
  fmt::print("bench dem --stripped{}: {} particles, {} steps, 1 thread, {:.3f} s\n", args.accounts ? " --accounts" : "",
             ref.size(), args.steps, wall);
  fmt::print("the same contact law without {}thread-count independence or list rebuilds, fused multiply-adds "
             "allowed: a bound for the engine, not the engine\n",
             args.accounts ? "" : "energy accounts, ");
  // The engine's `state:` line after the same steps agrees to round-off.
  if (args.accounts)
    fmt::print("state: E_kin {:.17g} E_pot {:.17g} dissipated {:.17g} + {:.17g} J\n", ref.kinetic_energy(),
               ref.potential_energy(), ref.dissipated_damping(), ref.dissipated_friction());
  else
    fmt::print("state: E_kin {:.17g} E_pot {:.17g} J\n", ref.kinetic_energy(), ref.potential_energy());
  fmt::print("particle-steps/s: {:.4e}\n", rate);
  return 0;
}

}  // namespace

int run_dem_bench(const DemBenchArgs& args) {
  if (args.stripped && args.threads != 1)
    throw Error("bench dem: the stripped reference runs on one thread (drop --threads with --stripped)");
  const contact::ContactModel m = contact::default_contact_model(args.law);
  if (args.stripped && m.index() != 0)
    throw Error("bench dem: the stripped reference is the linear law's (drop --law with --stripped)");
  omp_set_num_threads(args.threads);
  io::ParticleTable bed = io::read_particles_csv(args.bed);
  const double d = bed.d.at(0);
  for (double di : bed.d)
    if (di != d) throw Error("bench dem: the bed must be monodisperse");
  const double lx = args.box_x, ly = args.box_y;
  for (size_t i = 0; i < bed.size(); ++i)
    if (!(bed.x[i].x >= 0 && bed.x[i].x <= lx && bed.x[i].y >= 0 && bed.x[i].y <= ly && bed.x[i].z >= 0))
      throw Error(fmt::format("bench dem: particle {} of the bed lies outside the box {} x {} m (see --box-x, "
                              "--box-y)", i, lx, ly));

  // The box's walls, as planes (the stripped reference takes them as they are) and as the
  // engine's scene parts, in the same order.
  const std::vector<Plane> planes{{{0, 0, 0}, {1, 0, 0}},     {{lx, 0, 0}, {-1, 0, 0}}, {{0, 0, 0}, {0, 1, 0}},
                                  {{0, ly, 0}, {0, -1, 0}}, {{0, 0, 0}, {0, 0, 1}}};
  const char* names[] = {"x0", "x1", "y0", "y1", "floor"};
  geometry::Scene scene;
  int box = scene.add_body("box", geometry::Motion{});
  for (size_t k = 0; k < planes.size(); ++k)
    scene.add_part(box, names[k], geometry::make_half_space(planes[k].point, planes[k].normal));

  Species s{"bed", d, 1.0, 1500.0};
  DemParams p;
  p.dt = 1e-6;
  p.gravity = {0, 0, -9.81};
  p.skin = 0.1 * d;  // as the LAMMPS script: neighbor 0.1 d
  p.accounts = !args.no_accounts;
  p.domain = {{-0.01, -0.01, -0.01}, {lx + 0.01, ly + 0.01, 1.0}};
  DemSolver dem({s}, m, p, scene);
  for (size_t i = 0; i < bed.size(); ++i) dem.particles().add(static_cast<int64_t>(i), 0, s, bed.x[i]);

  dem.step();  // first build and forces, not timed
  if (args.stripped) return run_stripped(dem, planes, args);
  dem.timers().reset();
  Stopwatch clock;
  const std::clock_t cpu0 = std::clock();
  for (long k = 0; k < args.steps; ++k) {
    if (args.rebuild_every > 0 && k % args.rebuild_every == 0) dem.rebuild_lists_at_next_step();
    dem.step();
  }
  const double wall = clock.seconds();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const double rate = static_cast<double>(bed.size()) * args.steps / wall;
  EnergyBudget e = dem.energy();
  fmt::print("bench dem: {} particles of {:g} m, {} steps, {} thread(s), {:.3f} s, contact law {}{}\n", bed.size(),
             d, args.steps, args.threads, wall, dem.contact_law(), args.no_accounts ? ", no energy accounts" : "");
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
