#include "coupling/drag.hpp"

#include "core/error.hpp"

namespace cgdem::coupling {

DragLaw parse_drag_law(const std::string& name) {
  if (name == "ergun-wen-yu") return DragLaw::ErgunWenYu;
  if (name == "wen-yu") return DragLaw::WenYu;
  if (name == "ergun") return DragLaw::Ergun;
  throw Error("unknown drag law '" + name + "' (expected \"ergun-wen-yu\", \"wen-yu\" or \"ergun\")");
}

}  // namespace cgdem::coupling
