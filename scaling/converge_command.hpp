// `cgdem converge`: placeholder registration, being built (issue #5).
#pragma once
#include <CLI/CLI.hpp>

namespace cgdem::scaling {

class ConvergeCommand {
 public:
  explicit ConvergeCommand(CLI::App& app);  // adds the subcommand and its options to app
  bool selected() const { return sub_->parsed(); }
  int run() const;  // after parsing; throws cgdem::Error on bad input

 private:
  CLI::App* sub_;
};

}  // namespace cgdem::scaling
