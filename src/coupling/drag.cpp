#include "coupling/drag.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"

namespace cgdem::coupling {

std::vector<std::string> drag_law_names() {
  std::vector<std::string> names;
  for (const auto& row : kDragLaws) names.emplace_back(row.name);
  return names;
}

DragLaw parse_drag_law(const std::string& name) {
  for (const auto& row : kDragLaws)
    if (name == row.name) return row.law;
  throw Error(fmt::format("unknown drag law '{}' (allowed: {})", name, fmt::join(drag_law_names(), ", ")));
}

}  // namespace cgdem::coupling
