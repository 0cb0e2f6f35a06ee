#include "scaling/scale_command.hpp"

#include "core/error.hpp"

namespace cgdem::scaling {

ScaleCommand::ScaleCommand(CLI::App& app) : sub_(app.add_subcommand("scale", "(not available yet: being built, issue #5)")) {}

int ScaleCommand::run() const { throw Error("cgdem scale is not available yet (issue #5)"); }

}  // namespace cgdem::scaling
