#include "app/run_dem.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "io/particle_h5.hpp"
#include "io/snapshot_series.hpp"
#include "particles/particle_io.hpp"

namespace cgdem::app {

namespace {

// Stops the run on NaN/Inf or a runaway speed, naming the particle, step and time.
void check_health(const DemSolver& dem, double max_speed) {
  const Particles& p = dem.particles();
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 &x = p.x[i], &v = p.v[i];
    bool finite = std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(v.x) &&
                  std::isfinite(v.y) && std::isfinite(v.z);
    if (!finite || norm(v) > max_speed)
      throw RunError(fmt::format(
          "step {}, t = {:.6g} s: particle id {} has {} (x = [{:.4g}, {:.4g}, {:.4g}] m, |v| = {:.4g} m/s; "
          "output.max_speed = {:g}). The run stopped; the last good state is last_good.h5 in the output folder.",
          dem.steps(), dem.time(), p.id[i], finite ? "a runaway velocity" : "a non-finite position or velocity",
          x.x, x.y, x.z, norm(v), max_speed));
  }
}

// Particles whose centre lies inside a wall (tunnelled): counted, not hidden.
long count_inside_walls(const DemSolver& dem) {
  if (dem.scene().empty()) return 0;
  auto frame = dem.scene().at(dem.time());
  long n = 0;
  for (const auto& x : dem.particles().x)
    if (frame.phi(x) < 0) ++n;
  return n;
}

std::string energy_header() {
  return "t,E_kin_trans,E_kin_rot,E_pot,E_elastic,E_diss_damping,E_diss_friction,W_walls,E_balance,"
         "px,py,pz,mass,particles,removed,inside_walls";
}

}  // namespace

int run_dem_case(const DemCase& c, const RunInfo& info) {
  namespace fs = std::filesystem;
  fs::create_directories(c.output.dir);
  const std::string case_dir = fs::path(info.case_file).parent_path().string();
  io::write_file_atomic((fs::path(c.output.dir) / "config.resolved.toml").string(),
                        fmt::format("# cgdem {} resolved configuration of {}\n{}", kGitRevision, info.case_file,
                                    info.resolved_config));
  io::Attributes attrs{{"cgdem_revision", kGitRevision}, {"config", info.resolved_config}};

  Stopwatch setup_clock;
  auto dem = build_solver(c, case_dir.empty() ? "." : case_dir);
  fmt::print("cgdem {}: {} particles, {} species, {} wall parts, dt = {:g} s, t = {:g} .. {:g} s\n", kGitRevision,
             dem->particles().size(), c.species.size(), dem->scene().parts().size(), c.dem.dt, c.t_start, c.t_end);
  fmt::print("shortest collision time {:.4g} s ({:.1f} steps); set-up {:.2f} s\n", dem->min_collision_time(),
             dem->min_collision_time() / c.dem.dt, setup_clock.seconds());

  io::SnapshotSeries snapshots(c.output.dir, "particles", attrs);
  const std::string energy_path = (fs::path(c.output.dir) / "energy.csv").string();
  std::FILE* energy = std::fopen(energy_path.c_str(), "w");
  if (!energy) throw Error("cannot write " + energy_path);
  std::fprintf(energy, "# cgdem %s, case %s\n%s\n", kGitRevision, info.case_file.c_str(), energy_header().c_str());

  const bool tty = isatty(STDOUT_FILENO);
  const long total_steps = std::lround((c.t_end - c.t_start) / c.dem.dt);
  const long energy_every = std::max(1L, std::lround(c.output.energy_interval / c.dem.dt));
  const long snap_every = std::max(1L, std::lround(c.output.snapshot_interval / c.dem.dt));
  const std::string last_good = (fs::path(c.output.dir) / "last_good.h5").string();

  auto write_energy = [&]() {
    EnergyBudget e = dem->energy();
    std::fprintf(energy, "%.9g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%zu,%ld,%ld\n",
                 dem->time(), e.kinetic_translational, e.kinetic_rotational, e.potential, e.elastic,
                 e.dissipated_damping, e.dissipated_friction, e.work_walls, e.balance(), e.momentum.x, e.momentum.y,
                 e.momentum.z, e.mass, dem->particles().size(), dem->removed(), count_inside_walls(*dem));
    std::fflush(energy);
  };
  auto write_snapshot = [&]() {
    io::ParticleTable t = to_table(dem->particles());
    snapshots.write(dem->steps(), dem->time(), t);
    io::write_particles_h5(last_good, t, attrs);  // atomic: always a consistent restart state
  };

  check_health(*dem, c.output.max_speed);
  write_energy();
  write_snapshot();
  Stopwatch clock;
  double last_progress = 0;
  long particle_steps = 0;
  for (long s = 1; s <= total_steps; ++s) {
    dem->step();
    particle_steps += static_cast<long>(dem->particles().size());
    const bool snap = s % snap_every == 0 || s == total_steps;
    if (s % energy_every == 0 || snap) {
      check_health(*dem, c.output.max_speed);
      write_energy();
    }
    if (snap) write_snapshot();
    const double wall = clock.seconds();
    if ((tty && wall - last_progress > 0.5) || (!tty && wall - last_progress > c.output.progress_interval) ||
        s == total_steps) {
      last_progress = wall;
      double frac = static_cast<double>(s) / total_steps, rate = particle_steps / std::max(wall, 1e-9);
      std::string line = fmt::format("t = {:.5f} s  {:5.1f}%  {:.3g} particle-steps/s  ETA {:.0f} s", dem->time(),
                                     100 * frac, rate, wall * (1 - frac) / std::max(frac, 1e-9));
      if (tty) fmt::print("\r{}   ", line), std::fflush(stdout);
      else fmt::print("{}\n", line);
    }
  }
  if (tty) fmt::print("\n");
  std::fclose(energy);

  const double wall = clock.seconds();
  EnergyBudget e = dem->energy();
  fmt::print("\n{}", dem->timers().table("per-phase time (DEM)"));
  fmt::print("steps {}, wall {:.1f} s, {:.3g} particle-steps/s, neighbour-list builds {}\n", total_steps, wall,
             particle_steps / std::max(wall, 1e-9), dem->neighbor_builds());
  fmt::print("particles {} (left the domain: {}, centre inside a wall: {}), solid mass {:.6g} kg\n",
             dem->particles().size(), dem->removed(), count_inside_walls(*dem), e.mass);
  fmt::print("outputs in {}: energy.csv, particles.xdmf (+ particles_*.h5), last_good.h5, config.resolved.toml\n",
             c.output.dir);
  return 0;
}

}  // namespace cgdem::app
