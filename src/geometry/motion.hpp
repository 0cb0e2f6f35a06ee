// Prescribed rigid translation of a wall body.
//
// The velocity is piecewise linear in time through knots (t_k, U_k) and constant before
// the first and after the last knot; one knot is a constant velocity. The displacement
// X(t) = integral_0^t U dt' is evaluated exactly (trapezoids), so a body's position does
// not drift with the time step.
#pragma once
#include <vector>

#include "core/vec3.hpp"

namespace cgdem::geometry {

class Motion {
 public:
  Motion() : times_{0.0}, velocities_{Vec3{}} {}  // at rest
  static Motion constant(const Vec3& u) { return Motion({0.0}, {u}); }
  // Knots must have strictly increasing times; throws std::invalid_argument otherwise.
  Motion(std::vector<double> times, std::vector<Vec3> velocities);

  Vec3 velocity(double t) const;
  Vec3 displacement(double t) const;  // from t = 0
  bool is_static() const;
  // Upper bound of |U| over all time (used for neighbour-list margins).
  double max_speed() const;

 private:
  std::vector<double> times_;
  std::vector<Vec3> velocities_;
};

}  // namespace cgdem::geometry
