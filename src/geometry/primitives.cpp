// The rows of the wall-primitive registry (primitives.hpp) and their key readers.
#include "geometry/primitives.hpp"

#include <fmt/format.h>

#include "core/config.hpp"

namespace cgdem::geometry {

namespace {

constexpr double kMaxRadius = 1e3;  // m

ShapePtr read_box(const Section& s) {
  Vec3 lo = s.vec3("min"), hi = s.vec3("max");
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) s.fail("max", "must exceed min on every axis");
  return make_box(lo, hi);
}

ShapePtr read_half_space(const Section& s) {
  Vec3 p = s.vec3("point"), n = s.vec3("normal");
  if (!(norm(n) > 0)) s.fail("normal", "must be a non-zero vector (pointing out of the wall)");
  return make_half_space(p, n);
}

ShapePtr read_cylinder(const Section& s) {
  Vec3 p0 = s.vec3("p0"), p1 = s.vec3("p1");
  double r = s.number("radius", Range::open_closed(0, kMaxRadius));
  if (!(norm(p1 - p0) > 0)) s.fail("p1", "must differ from p0");
  return make_cylinder(p0, p1, r);
}

ShapePtr read_sphere(const Section& s) {
  return make_sphere(s.vec3("centre"), s.number("radius", Range::open_closed(0, kMaxRadius)));
}

ShapePtr read_cone(const Section& s) {
  Vec3 p0 = s.vec3("p0"), p1 = s.vec3("p1");
  double r0 = s.number("radius0", Range::closed(0, kMaxRadius)), r1 = s.number("radius1", Range::closed(0, kMaxRadius));
  if (!(norm(p1 - p0) > 0)) s.fail("p1", "must differ from p0");
  if (!(r0 + r1 > 0)) s.fail("radius1", "radius0 and radius1 cannot both be 0");
  return make_cone(p0, p1, r0, r1);
}

ShapePtr read_ring(const Section& s) {
  Vec3 p0 = s.vec3("p0"), p1 = s.vec3("p1");
  double ri = s.number("radius_inner", Range::open_closed(0, kMaxRadius));
  double ro = s.number("radius_outer", Range::open_closed(0, kMaxRadius));
  if (!(ro > ri)) s.fail("radius_outer", fmt::format("must exceed radius_inner ({:g})", ri));
  if (!(norm(p1 - p0) > 0)) s.fail("p1", "must differ from p0");
  return make_ring(p0, p1, ri, ro);
}

const PrimitiveRow kPrimitives[] = {
    {"box", "axis-aligned solid box; keys min, max", &read_box, "min = [0, 0, 0]\nmax = [1, 2, 3]"},
    {"halfspace", "the solid behind a plane; keys point, normal (pointing out of the solid)", &read_half_space,
     "point = [0, 0, 1]\nnormal = [0, 0, 2]"},
    {"cylinder", "solid capped cylinder; keys p0, p1 (axis ends), radius", &read_cylinder,
     "p0 = [0, 0, 0]\np1 = [0, 0, 2]\nradius = 1.0"},
    {"sphere", "solid sphere; keys centre, radius", &read_sphere, "centre = [0, 0, 0]\nradius = 1.0"},
    {"cone", "solid capped cone (frustum, e.g. a hopper); keys p0, p1 (axis ends), radius0, radius1 (one may be 0)",
     &read_cone, "p0 = [0, 0, 0]\np1 = [0, 0, 2]\nradius0 = 1.0\nradius1 = 0.25"},
    {"ring", "solid ring between two radii (a tube wall, or a plate with a round hole); keys p0, p1 (axis ends), "
     "radius_inner, radius_outer",
     &read_ring, "p0 = [0, 0, 0]\np1 = [0, 0, 0.5]\nradius_inner = 1.0\nradius_outer = 3.0"},
};

}  // namespace

std::span<const PrimitiveRow> wall_primitives() { return kPrimitives; }

std::vector<std::string> wall_primitive_names() {
  std::vector<std::string> names;
  for (const PrimitiveRow& r : kPrimitives) names.emplace_back(r.name);
  return names;
}

std::string wall_primitive_help() {
  std::string help;
  for (const PrimitiveRow& r : kPrimitives) help += fmt::format("  {:<14} {}\n", r.name, r.doc);
  return help;
}

ShapePtr read_primitive(const Section& s) {
  const std::string type = s.string("type", wall_primitive_names());
  ShapePtr shape;
  for (const PrimitiveRow& r : kPrimitives)
    if (r.name == type) shape = r.read(s);
  if (s.boolean_or("inside_free", false)) shape = make_complement(shape);
  return shape;
}

}  // namespace cgdem::geometry
