// The [contact] reader of the linear law (the registry's parameter reader, laws.hpp).
#include "contact/linear_law.hpp"

#include "core/config.hpp"

namespace cgdem::contact {

LinearSpringDashpot::Material LinearSpringDashpot::read(const Section& s) {
  constexpr double kMaxStiffness = 1e10;  // N/m
  constexpr double kMaxFriction = 5.0;    // Coulomb coefficient
  Material m;
  m.stiffness = s.number("stiffness", Range::open_closed(0, kMaxStiffness));
  m.restitution = s.number("restitution", Range::open_closed(0, 1));
  m.friction = s.number("friction", Range::closed(0, kMaxFriction));
  m.wall_restitution = s.number_or("wall_restitution", m.restitution, Range::open_closed(0, 1));
  m.wall_friction = s.number_or("wall_friction", m.friction, Range::closed(0, kMaxFriction));
  return m;
}

}  // namespace cgdem::contact
