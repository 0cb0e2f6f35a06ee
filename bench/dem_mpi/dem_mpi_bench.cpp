// Dense-bed DEM benchmark over MPI ranks (issue 6; shared/bench/dem_bed/README.md): the
// same bed, walls, material and step as `cgdem bench dem`, stepped by
// parallel::DistributedDem on a decomposition of the DEM domain into N x 1 x 1 blocks
// (cuts across x, the bed's longer side; on 2 ranks the cut is the bed's middle plane).
//   mpirun -np N bench_dem_mpi BED.csv [STEPS=2000]
// Single-threaded ranks. The figure is particles x steps / wall seconds of the stepping
// loop on rank 0 (every rank steps together: the list builds are collective), reading the
// bed and the first step not counted. On 1 rank the run is `cgdem bench dem`'s, bit for
// bit: compare the state lines.
#include <fmt/format.h>
#include <mpi.h>
#include <omp.h>

#include <cstdlib>
#include <ctime>
#include <string>

#include "core/error.hpp"
#include "core/timers.hpp"
#include "io/particle_csv.hpp"
#include "solvers/dem_mpi/distributed_dem.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem {
namespace {

int run(int argc, char** argv) {
  int rank = 0, size = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (argc < 2) throw Error("usage: mpirun -np N bench_dem_mpi BED.csv [STEPS]");
  const std::string bed_path = argv[1];
  const long steps = argc > 2 ? std::atol(argv[2]) : 2000;
  if (steps < 1) throw Error(fmt::format("bench_dem_mpi: {} steps", steps));
  omp_set_num_threads(1);

  const io::ParticleTable bed = io::read_particles_csv(bed_path);
  const double d = bed.d.at(0);
  for (double di : bed.d)
    if (di != d) throw Error("bench_dem_mpi: the bed must be monodisperse");
  geometry::Scene scene;
  const int box = scene.add_body("box", geometry::Motion{});
  scene.add_part(box, "x0", geometry::make_half_space({0, 0, 0}, {1, 0, 0}));
  scene.add_part(box, "x1", geometry::make_half_space({0.010, 0, 0}, {-1, 0, 0}));
  scene.add_part(box, "y0", geometry::make_half_space({0, 0, 0}, {0, 1, 0}));
  scene.add_part(box, "y1", geometry::make_half_space({0, 0.006, 0}, {0, -1, 0}));
  scene.add_part(box, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  const Species s{"bed", d, 1.0, 1500.0};
  const MaterialParams m{50.0, 0.9, 0.3, 0.9, 0.3};
  DemParams p;
  p.dt = 1e-6;
  p.gravity = {0, 0, -9.81};
  p.skin = 0.1 * d;
  p.domain = {{-0.01, -0.01, -0.01}, {0.02, 0.016, 1.0}};  // as bench/dem/dem_bench.cpp
  DemSolver dem({s}, m, p, scene);
  const parallel::Decomposition dec(p.domain, {size, 1, 1});
  for (size_t i = 0; i < bed.size(); ++i)
    if (dec.owner_of(bed.x[i]) == rank) dem.particles().add(static_cast<int64_t>(i), 0, s, bed.x[i]);
  parallel::DistributedDem hook(MPI_COMM_WORLD, dec, dem);

  dem.step();  // first build and forces, not timed
  dem.timers().reset();
  hook.timers().reset();
  MPI_Barrier(MPI_COMM_WORLD);
  Stopwatch clock;
  const std::clock_t cpu0 = std::clock();
  for (long k = 0; k < steps; ++k) dem.step();
  MPI_Barrier(MPI_COMM_WORLD);
  const double wall = clock.seconds();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const EnergyBudget e = parallel::global_energy(MPI_COMM_WORLD, dem);
  const long contacts = parallel::global_contacts(MPI_COMM_WORLD, dem);
  long owned = static_cast<long>(dem.owned()), ghosts = static_cast<long>(dem.particles().size()) - owned;
  long owned_max = owned, ghosts_sum = ghosts, migrated = hook.counters().parcels_sent;
  MPI_Allreduce(MPI_IN_PLACE, &owned_max, 1, MPI_LONG, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &ghosts_sum, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &migrated, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  double cpu_sum = cpu;
  MPI_Allreduce(MPI_IN_PLACE, &cpu_sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) {
    const double rate = static_cast<double>(bed.size()) * steps / wall;
    fmt::print("bench dem mpi: {} particles of {:g} m, {} steps, {} rank(s) ({} x 1 x 1 blocks), 1 thread each, {:.3f} s\n",
               bed.size(), d, steps, size, size, wall);
    fmt::print("parcels per rank at most {}, ghosts {} (all ranks), parcels migrated {}, list builds {}, contacts {}\n",
               owned_max, ghosts_sum, migrated, dem.neighbor_builds(), contacts);
    fmt::print("processor time {:.3f} s summed over the ranks ({:.2f} of {} ranks busy)\n", cpu_sum, cpu_sum / wall,
               size);
    fmt::print("{}", dem.timers().table("per-phase time (rank 0; the exchanges are in 'neighbour lists')"));
    fmt::print("{}", hook.timers().table("inside 'neighbour lists': the hook's calls (rank 0)"));
    fmt::print("state: E_kin {:.17g} E_pot {:.17g} dissipated {:.17g} + {:.17g} J\n",
               e.kinetic_translational + e.kinetic_rotational, e.potential, e.dissipated_damping,
               e.dissipated_friction);
    fmt::print("particle-steps/s: {:.4e}\n", rate);
  }
  return 0;
}

}  // namespace
}  // namespace cgdem

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rc = 0;
  try {
    rc = cgdem::run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_dem_mpi: {}\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return rc;
}
