// A stripped reference of the DEM step, for the dense-bed benchmark only: how fast the
// same contact law can go on this machine when everything the engine adds to it is left
// out. It is the bound that the engine's figure is read against (docs/dem_performance.md
// section 7), not a solver: `cgdem bench dem --stripped` runs it.
//
// Same physics as DemSolver on a bed of one species in a box of planar walls: velocity
// Verlet, linear spring-dashpot normal force, tangential spring with history, rotation of
// the history into the tangent plane, Coulomb limit (contact/linear_law.hpp), gravity. Left out:
//   * the energy accounts (dissipated energy, wall work): the history is xi alone (3
//     doubles per entry instead of 8), and no per-contact bookkeeping; optional (the
//     `accounts` variant keeps the dissipated energies, as the engine books them);
//   * independence of the thread count and of the instruction set: one thread, fused
//     multiply-adds allowed, forces scattered straight into both particles;
//   * list rebuilds, moving walls, general signed-distance walls (planes only), several
//     species, coarse-graining ratios, air, periodic axes, ghosts, checkpoints.
// Each of these costs the engine time that this reference does not spend. The lists,
// particle order and starting state are the engine's own (taken after its first step), so
// both integrate the same system: their trajectories agree to round-off
// (tests/bench/stripped_dem_test.cpp).
#pragma once
#include <vector>

#include "core/vec3.hpp"
#include "solvers/dem/dem_solver.hpp"

namespace cgdem::bench {

struct Plane {
  Vec3 point, normal;  // unit normal into the particles' side
};

class StrippedDem {
 public:
  // The state of `from` (stepped at least once: its lists are built), whose walls are the
  // given planes (the caller built its scene from the same list).
  // With `accounts`, it also keeps the engine's energy accounts (dissipated by the normal
  // dashpots and tangentially, second-order bookkeeping of contact/linear_law.hpp): the history
  // is then 8 doubles per entry, as in the engine, and each contact books its energy.
  StrippedDem(const DemSolver& from, std::vector<Plane> walls, bool accounts = false);
  // One step of velocity Verlet. Throws when a particle has moved more than half the
  // skin since the lists were built (this reference does not rebuild them).
  void step();
  // Kinetic (translation + rotation) and gravitational potential energy.
  double kinetic_energy() const;
  double potential_energy() const;
  // Energy dissipated since the engine's start (its accounts are taken over; 0 without
  // the accounts).
  double dissipated_damping() const;
  double dissipated_friction() const;
  Vec3 position(int i) const;
  Vec3 velocity(int i) const;
  Vec3 angular_velocity(int i) const;
  int size() const { return n_; }

 private:
  void forces();

  bool accounts_;
  int n_ = 0;
  double dt_, skin_;
  Vec3 g_;
  contact::Params pair_, wall_;
  double radius_, mass_, inv_mass_, inv_inertia_;
  // Particle fields as structure of arrays (x0: positions at the list build).
  std::vector<double> x_[3], v_[3], w_[3], f_[3], t_[3], x0_[3];
  std::vector<double> damp_, fric_;  // energy dissipated, per particle
  // Pair entries (the engine's half lists): offsets per owner, owner and partner per
  // entry, the history (xi; with the accounts ft, vn, ftvt too).
  std::vector<int> offset_, owner_, partner_;
  std::vector<double> hist_[8];
  // Per entry of the current block of owners: force on the owner, n x F_t, energies.
  std::vector<double> share_[8];
  std::vector<Plane> walls_;
  // Per wall: the candidate particles (the engine's, fixed) and their histories.
  struct WallCandidates {
    std::vector<int> particle;
    std::vector<double> hist[8];
  };
  std::vector<WallCandidates> walls_cand_;
};

}  // namespace cgdem::bench
