// `cgdem compare RUN_A RUN_B [RUN_C ...] [--labels a,b,...] [--output DIR]`: finished runs of
// `cgdem run` side by side against the first one (the same case with air and with
// --set air.enabled=false, say): the resolved configuration keys that differ, every metric
// with its difference, the diagnostics curves at fixed times and their normalised L2
// distances, as compare.md with CSV tables and plots (compare_study.hpp, compare_report.hpp).
// Runs nothing. Default DIR: compare_<name of RUN_A>_<name of RUN_B> in the current folder.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace cgdem::scaling {

class CompareCommand {
 public:
  explicit CompareCommand(CLI::App& app);  // adds the subcommand and its options to app
  ~CompareCommand();
  bool selected() const { return sub_->parsed(); }
  int run() const;  // after parsing; throws cgdem::Error on bad input

 private:
  struct Options;  // the parsed values (compare_command.cpp); CLI11 keeps pointers to them
  CLI::App* sub_;
  std::unique_ptr<Options> o_;
};

}  // namespace cgdem::scaling
