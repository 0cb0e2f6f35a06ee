// Every field of Particles, in declaration order, for code that must move a parcel whole
// (the migration buffers and their tests). The structured binding names each member once:
// a field added to Particles stops this compiling ("19 names required") until it is named
// here, so no copy of a parcel made through it can leave a new field behind.
#pragma once
#include <concepts>
#include <type_traits>

#include "particles/particles.hpp"

namespace cgdem::parallel {

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

}  // namespace cgdem::parallel
