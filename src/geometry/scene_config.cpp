#include "geometry/scene_config.hpp"

#include <fmt/format.h>

#include "geometry/die_filling.hpp"
#include "geometry/primitives.hpp"

namespace cgdem::geometry {

namespace {

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
      scene.add_part(id, name, read_primitive(p));
    }
  }
  return scene;
}

}  // namespace cgdem::geometry
