// Particle storage: structure of arrays, one vector per field, indexed 0..size()-1.
// Local indices change when the neighbour list re-sorts particles in space; `id` is the
// stable identity (contact history, output and restarts use it).
#pragma once
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
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
  // not listed in `order` are dropped. Each field is gathered in parallel (OpenMP).
  void reorder(const std::vector<int>& order);
  // Storage the reorder gathers into, one array per element type (after each field the
  // field's old storage becomes the next one's). A caller that sorts the particles again
  // and again (the neighbour list builds) keeps it, and a sort then allocates nothing;
  // contents meaningless.
  using ReorderScratch = std::tuple<std::vector<int64_t>, std::vector<int>, std::vector<double>, std::vector<Vec3>>;
  // The same, with storage the caller keeps.
  void reorder(const std::vector<int>& order, ReorderScratch& scratch);
  // Appends every parcel of `other` (all fields), in its order.
  void append(const Particles& other);
};

// Every member of Particles as a tuple of references, in declaration order. The one place
// that lists them: for_each_field below, and through it reorder(), append(), the
// checkpoint (dem_checkpoint.cpp) and the migration buffers (src/parallel). The
// structured binding names each member once, so adding a member to Particles stops this
// compiling ("N names required") until it is named here; no code that moves a parcel
// whole can then leave it behind.
template <class P>
  requires std::same_as<std::remove_const_t<P>, Particles>
auto field_refs(P& p) {
  auto& [id, species, x, v, omega, force, torque, f_ext, drag, u_fluid, j_drag, radius, inv_mass, inv_inertia,
         e_damping, e_friction, w_walls, w_fluid] = p;
  return std::tie(id, species, x, v, omega, force, torque, f_ext, drag, u_fluid, j_drag, radius, inv_mass,
                  inv_inertia, e_damping, e_friction, w_walls, w_fluid);
}

// f(field) for every member of p, in declaration order.
template <class P, class F>
void for_each_field(P& p, F&& f) {
  std::apply([&](auto&... field) { (f(field), ...); }, field_refs(p));
}

// f(field of a, same field of b) for every member, in declaration order.
template <class P, class Q, class F>
void for_each_field(P& a, Q& b, F&& f) {
  auto ta = field_refs(a);
  auto tb = field_refs(b);
  [&]<size_t... I>(std::index_sequence<I...>) {
    (f(std::get<I>(ta), std::get<I>(tb)), ...);
  }(std::make_index_sequence<std::tuple_size_v<decltype(ta)>>{});
}

}  // namespace cgdem
