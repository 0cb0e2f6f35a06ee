#include "scaling/spectrum_command.hpp"

#include "core/error.hpp"

namespace cgdem::scaling {

SpectrumCommand::SpectrumCommand(CLI::App& app) : sub_(app.add_subcommand("spectrum", "(not available yet: being built, issue #5)")) {}

int SpectrumCommand::run() const { throw Error("cgdem spectrum is not available yet (issue #5)"); }

}  // namespace cgdem::scaling
