// Solid shapes described by signed distance functions (SDF).
//
// Convention of a Shape (the solid's own SDF): s(x) < 0 inside the solid, s(x) > 0
// outside, |s| the distance to the surface (exact for primitives, a lower bound for CSG
// combinations away from the surface). The paper's phi_SDF (eq. 15), positive in the
// region particles and air may occupy, is s of the union of all wall solids.
//
//   primitives  HalfSpace, Box, Cylinder (capped), Sphere, Cone (capped, cone.cpp)
//   CSG         Union = min(a, b), Intersection = max(a, b), Difference = max(a, -b),
//               Complement = -a (e.g. the inside of a closed container)
//
// A shape is immutable and defined in its body's frame; motion is handled by Body.
#pragma once
#include <memory>
#include <string>

#include "core/vec3.hpp"

namespace cgdem::geometry {

struct Aabb {
  Vec3 lo{-INFINITY, -INFINITY, -INFINITY}, hi{INFINITY, INFINITY, INFINITY};
  // Euclidean distance from x to the box (0 inside).
  double distance(const Vec3& x) const;
  bool contains(const Vec3& x) const {
    return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
  }
  Aabb shifted(const Vec3& d) const { return {lo + d, hi + d}; }
};

class Shape {
 public:
  virtual ~Shape() = default;
  // Signed distance s(x), negative inside the solid.
  virtual double distance(const Vec3& x) const = 0;
  // Signed distance and its gradient (unit length wherever the SDF is exact).
  virtual double distance_gradient(const Vec3& x, Vec3& grad) const = 0;
  // A box containing the solid (may be unbounded).
  virtual Aabb bounds() const = 0;
  virtual std::string describe() const = 0;
  // True for a solid whose interior is a product of one open interval per axis (an
  // axis-aligned box); inside_along(a, v) then says whether the coordinate v of axis a (in
  // the shape's frame) lies in that axis's interval, with the arithmetic of distance():
  // distance(x) < 0 exactly when it holds on all three axes. A lattice of n^3 points is
  // then tested with 3n calls (fluid/ibm.cpp). False (and unused) for every other shape.
  virtual bool axis_separable() const { return false; }
  virtual bool inside_along(int axis, double v) const {
    (void)axis, (void)v;
    return false;
  }
};

using ShapePtr = std::shared_ptr<const Shape>;

// Solid on the side opposite to `normal` of the plane through `point`; `normal` points
// out of the solid into the free region.
ShapePtr make_half_space(const Vec3& point, const Vec3& normal);
// Axis-aligned solid box [lo, hi].
ShapePtr make_box(const Vec3& lo, const Vec3& hi);
// Solid capped cylinder with axis from p0 to p1.
ShapePtr make_cylinder(const Vec3& p0, const Vec3& p1, double radius);
ShapePtr make_sphere(const Vec3& centre, double radius);
// Solid capped cone (frustum) with axis from p0 (radius r0) to p1 (radius r1); one radius
// may be 0 (cone.cpp).
ShapePtr make_cone(const Vec3& p0, const Vec3& p1, double r0, double r1);
// Solid ring (thick-walled tube; with a large outer radius, a plate with a round hole)
// between radii r_in > 0 and r_out about the axis from p0 to p1 (ring.cpp).
ShapePtr make_ring(const Vec3& p0, const Vec3& p1, double r_in, double r_out);
ShapePtr make_union(ShapePtr a, ShapePtr b);
ShapePtr make_intersection(ShapePtr a, ShapePtr b);
ShapePtr make_difference(ShapePtr a, ShapePtr b);  // a minus b
ShapePtr make_complement(ShapePtr a);

}  // namespace cgdem::geometry
