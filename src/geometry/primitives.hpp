// The wall-primitive registry: every solid a [[walls.body.part]] may name with
// type = "NAME" (scene_config.hpp). A row gives the name, one line of documentation and
// the reader of the part's own keys, which returns the solid (shape.hpp). The part reader,
// its "expected one of ..." message and `cgdem run --help` take the names from the table.
//
// Adding a primitive: its Shape and make_ function (shape.hpp declares the factories; the
// classes live in shape.cpp or a file of their own, as cone.cpp), and one row in
// primitives.cpp.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/shape.hpp"

namespace cgdem {
class Section;
}

namespace cgdem::geometry {

struct PrimitiveRow {
  std::string_view name;     // the value of type = "..."
  std::string_view doc;      // one line: what it is and its keys
  ShapePtr (*read)(const Section& part);
  std::string_view example;  // its keys for a unit-sized solid, as TOML (tests/geometry)
};

std::span<const PrimitiveRow> wall_primitives();
std::vector<std::string> wall_primitive_names();
// "NAME  doc" per primitive, one a line (for --help).
std::string wall_primitive_help();
// A part's solid: its type (a row's name) and that primitive's keys; inside_free = true
// makes the inside of the shape the free region (any primitive).
ShapePtr read_primitive(const Section& part);

}  // namespace cgdem::geometry
