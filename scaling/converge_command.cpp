#include "scaling/converge_command.hpp"

#include "core/error.hpp"

namespace cgdem::scaling {

ConvergeCommand::ConvergeCommand(CLI::App& app) : sub_(app.add_subcommand("converge", "(not available yet: being built, issue #5)")) {}

int ConvergeCommand::run() const { throw Error("cgdem converge is not available yet (issue #5)"); }

}  // namespace cgdem::scaling
