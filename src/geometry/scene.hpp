// The wall geometry shared by the particles (signed distance, eqs. 15-17) and the air
// (immersed-boundary volume fraction alpha, eqs. 18-20).
//
// A Scene is a list of rigid Bodies; a Body is a list of Parts (each a Shape) that move
// together with a prescribed translation. Particle-wall contact is evaluated per Part,
// so a concave corner is best built from two parts (each contact keeps its own history),
// while the air sees the union of all parts:
//   phi(x, t)   = min over parts of s_part(x - X_body(t))      (> 0 in the free region)
//   alpha(cell) = volume fraction of the cell inside any part
//   U_B(x, t)   = velocity of the body whose part is nearest to x
#pragma once
#include <string>
#include <vector>

#include "geometry/motion.hpp"
#include "geometry/shape.hpp"

namespace cgdem::geometry {

struct Part {
  std::string name;
  ShapePtr shape;
  int body = 0;
};

struct Body {
  std::string name;
  Motion motion;
  std::vector<int> parts;
};

class Scene {
 public:
  // Positions of every body at one instant: evaluated once per step, then shared.
  struct Frame {
    const Scene* scene = nullptr;
    double t = 0;
    std::vector<Vec3> offset, velocity;  // per body

    // Signed distance of one part and its gradient, in world coordinates.
    double part_distance(int part, const Vec3& x, Vec3& grad) const;
    double part_distance(int part, const Vec3& x) const;
    Vec3 part_velocity(int part) const { return velocity[scene->parts()[part].body]; }
    Aabb part_bounds(int part) const;
    // Shape::axis_separable / inside_along of a part, in world coordinates: with them,
    // part_distance(part, x) < 0 exactly when part_inside_along holds for x's three axes.
    bool part_separable(int part) const { return scene->parts()[part].shape->axis_separable(); }
    bool part_inside_along(int part, int axis, double v) const {
      const Part& p = scene->parts()[part];
      return p.shape->inside_along(axis, v - offset[p.body][axis]);
    }
    // phi of eq. (15): min over parts (+inf when the scene is empty).
    double phi(const Vec3& x) const;
    // Wall velocity U_B at x: that of the nearest part's body.
    Vec3 wall_velocity(const Vec3& x) const;
    // Fraction of the axis-aligned box [lo, hi] inside the walls, by n^3 midpoint samples
    // (exact 0 or 1 when the box is farther than its half-diagonal from every surface).
    double solid_fraction(const Vec3& lo, const Vec3& hi, int n) const;
  };

  int add_body(const std::string& name, Motion motion);
  int add_part(int body, const std::string& name, ShapePtr shape);

  const std::vector<Part>& parts() const { return parts_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  bool empty() const { return parts_.empty(); }
  // Whether part p belongs to a body that never moves.
  bool part_is_static(int p) const { return bodies_[parts_[p].body].motion.is_static(); }
  // Whether two sets of body offsets (Frame::offset) place every static body alike: caches
  // of the static walls stay valid between them.
  bool same_static_placement(const std::vector<Vec3>& a, const std::vector<Vec3>& b) const;
  Frame at(double t) const;
  std::string describe() const;

 private:
  std::vector<Body> bodies_;
  std::vector<Part> parts_;
};

}  // namespace cgdem::geometry
