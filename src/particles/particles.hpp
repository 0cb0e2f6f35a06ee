// Particle storage: structure of arrays, one vector per field, indexed 0..size()-1.
// Local indices change when the neighbour list re-sorts particles in space; `id` is the
// stable identity (contact history, output and restarts use it).
#pragma once
#include <concepts>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/vec3.hpp"
#include "particles/species.hpp"

namespace cgdem {

struct Particles {
  std::vector<int64_t> id;
  std::vector<int> species;
  std::vector<Vec3> x, v, omega;   // position [m], velocity [m/s], angular velocity [1/s]
  std::vector<Vec3> force, torque;  // accumulated in the force pass [N], [N m]
  std::vector<Vec3> f_ext;          // external force set by a coupling (pressure gradient) [N]
  // Linear drag set by a coupling, F_D = drag (u_fluid - v), integrated implicitly in the
  // kick (DemSolver::kick); drag = 0 means no air.
  std::vector<double> drag;         // V beta / (1 - eps) [kg/s], paper eq. (8)
  std::vector<Vec3> u_fluid;        // air velocity at the particle [m/s]
  std::vector<Vec3> j_drag;         // drag impulse received since the coupling reset it [N s]
  std::vector<double> radius, inv_mass, inv_inertia;
  // Running energy totals per particle (summed in a fixed order for diagnostics, so the
  // result does not depend on the number of threads) [J].
  std::vector<double> e_damping, e_friction, w_walls;
  std::vector<double> w_fluid;      // work done on the particle by drag and f_ext [J]

  size_t size() const { return x.size(); }
  void add(int64_t pid, int sp, const Species& s, const Vec3& pos, const Vec3& vel = {}, const Vec3& w = {});
  // Reorder every field: new index i takes the particle at old index order[i]. Particles
  // not listed in `order` are dropped.
  void reorder(const std::vector<int>& order);
};

// Calls f(field) on every member of Particles, in declaration order. The one place that
// lists them: reorder(), the checkpoint (dem_checkpoint.cpp) and the migration buffers
// (src/parallel/migration.cpp) all go through it. The structured binding names each
// member once, so adding a member to Particles stops this compiling ("N names required")
// until it is named here; no code that moves a parcel whole can then leave it behind.
template <class P, class F>
  requires std::same_as<std::remove_const_t<P>, Particles>
void for_each_field(P& p, F&& f) {
  auto& [id, species, x, v, omega, force, torque, f_ext, drag, u_fluid, j_drag, radius, inv_mass, inv_inertia,
         e_damping, e_friction, w_walls, w_fluid] = p;
  f(id);
  f(species);
  f(x);
  f(v);
  f(omega);
  f(force);
  f(torque);
  f(f_ext);
  f(drag);
  f(u_fluid);
  f(j_drag);
  f(radius);
  f(inv_mass);
  f(inv_inertia);
  f(e_damping);
  f(e_friction);
  f(w_walls);
  f(w_fluid);
}

}  // namespace cgdem
