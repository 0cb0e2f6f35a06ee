#include "geometry/scene_config.hpp"

#include <fmt/format.h>

#include "geometry/die_filling.hpp"

namespace cgdem::geometry {

namespace {

ShapePtr read_shape(const Section& s) {
  std::string type = s.string("type", {"box", "halfspace", "cylinder", "sphere"});
  ShapePtr shape;
  if (type == "box") {
    Vec3 lo = s.vec3("min"), hi = s.vec3("max");
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) s.fail("max", "must exceed min on every axis");
    shape = make_box(lo, hi);
  } else if (type == "halfspace") {
    Vec3 p = s.vec3("point"), n = s.vec3("normal");
    if (!(norm(n) > 0)) s.fail("normal", "must be a non-zero vector (pointing out of the wall)");
    shape = make_half_space(p, n);
  } else if (type == "cylinder") {
    Vec3 p0 = s.vec3("p0"), p1 = s.vec3("p1");
    double r = s.number("radius", Range::open_closed(0, 1e3));
    if (!(norm(p1 - p0) > 0)) s.fail("p1", "must differ from p0");
    shape = make_cylinder(p0, p1, r);
  } else {
    shape = make_sphere(s.vec3("centre"), s.number("radius", Range::open_closed(0, 1e3)));
  }
  if (s.boolean_or("inside_free", false)) shape = make_complement(shape);
  return shape;
}

Motion read_motion(const Section& b) {
  if (b.has("times") || b.has("velocities")) {
    if (b.has("velocity")) b.fail("velocity", "give either velocity or times/velocities, not both");
    auto times = b.numbers("times");
    auto vel = b.vec3_list("velocities");
    if (vel.size() != times.size()) b.fail("velocities", fmt::format("expected {} velocities (one per time), got {}", times.size(), vel.size()));
    try {
      return Motion(times, vel);
    } catch (const std::invalid_argument& e) {
      b.fail("times", e.what());
    }
  }
  return Motion::constant(b.vec3_or("velocity", {0, 0, 0}));
}

}  // namespace

Scene read_scene(const Section& walls) {
  Scene scene;
  if (auto df = walls.optional_section("die_filling")) add_die_filling(scene, read_die_filling(*df));
  for (const Section& b : walls.sections("body")) {
    int id = scene.add_body(b.string("name"), read_motion(b));
    auto parts = b.sections("part");
    if (parts.empty()) b.fail("part", "a body needs at least one [[walls.body.part]]");
    int k = 0;
    for (const Section& p : parts) {
      std::string name = p.string_or("name", fmt::format("part{}", k++));
      scene.add_part(id, name, read_shape(p));
    }
  }
  return scene;
}

}  // namespace cgdem::geometry
