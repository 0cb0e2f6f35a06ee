// Reading the [walls] section of a case file into a Scene.
//
//   [walls]
//   die_filling = { ... }          # optional: the paper's die-filling geometry (die_filling.hpp)
//   [[walls.body]]                 # any number of rigid bodies
//   name = "box"
//   velocity = [0, 0, 0]           # constant [m/s], or piecewise linear:
//   times = [0.0, 0.01]            #   knots [s]
//   velocities = [[0,0,0], [0.1,0,0]]
//   [[walls.body.part]]            # the body's parts (each its own contact)
//   type = "box"                   # a row of the wall-primitive registry (primitives.hpp),
//   min = [...]                    #   with that primitive's keys
//   inside_free = false            # true: the inside of the shape is the free region
#pragma once
#include "core/config.hpp"
#include "geometry/scene.hpp"

namespace cgdem::geometry {

Scene read_scene(const Section& walls);

}  // namespace cgdem::geometry
