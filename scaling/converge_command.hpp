// `cgdem converge CASE.toml --vary key.path=v1,v2,v3[,...] --metric NAME [--metric ...]`
//
// A refinement study: runs the case once per level of one key (in-process, as `cgdem run`
// would, with --set applied to every run and the level applied last) into
// DIR/<key>=<value>/, reads each run's metrics.csv and reports per metric the values, their
// differences, the observed order and Richardson-extrapolated value of every consecutive
// triple of levels, and the grid convergence index (scaling/richardson.hpp). Writes
// DIR/converge.csv and DIR/converge.md.
//
// h of a level (the discretisation parameter the order refers to), --h-from:
//   value    (default) the varied value itself: a cell size or a time step (air.dx, flow.dt)
//   1/value  its inverse: a cell count (flow.n)
//   NAME     the metric NAME of each run's metrics.csv (e.g. dx_m, dt_s)
// Other options: --exact NAME=VALUE (the known limit of a metric: adds a least-squares fit
// of ln|f - VALUE| against ln h over all levels), --reuse (a level whose folder holds a
// metrics.csv and a config.resolved.toml equal to the one it would now write is not rerun),
// --output DIR (default out/converge_<case name>), --threads N.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

namespace cgdem::scaling {

class ConvergeCommand {
 public:
  explicit ConvergeCommand(CLI::App& app);  // adds the subcommand and its options to app
  bool selected() const { return sub_->parsed(); }
  int run() const;  // after parsing; throws cgdem::Error on bad input

 private:
  struct Options {
    std::string case_file, vary, output, h_from = "value";
    std::vector<std::string> metrics, sets, exact;
    bool reuse = false;
    int threads = 0;
  };
  CLI::App* sub_;
  std::unique_ptr<Options> o_;  // CLI11 keeps pointers to these: a stable address
};

}  // namespace cgdem::scaling
