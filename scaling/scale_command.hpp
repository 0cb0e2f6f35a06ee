// `cgdem scale CASE.toml --ratios 1,2,3 [--simply-large 3]`: runs (or picks up finished
// runs of) the same case at each coarse-grain ratio l — same total mass, geometry and grid —
// plus optionally the simply-large system, and writes the consistency report (scale.md,
// CSVs, plots). The steps: scale_runs.hpp (derived cases, running, pick-up),
// scale_study.hpp (budgets, observables, POD, verdicts), scale_report.hpp (files).
#pragma once
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

namespace cgdem::scaling {

class ScaleCommand {
 public:
  explicit ScaleCommand(CLI::App& app);  // adds the subcommand and its options to app
  bool selected() const { return sub_->parsed(); }
  int run() const;  // after parsing; throws cgdem::Error on bad input

 private:
  CLI::App* sub_;
  std::string case_file_, output_;
  std::vector<double> ratios_{1, 2, 3};
  double simply_large_ = 0;
  std::vector<std::string> sets_, thresholds_;
  bool report_only_ = false, no_plots_ = false;
  double pod_dx_ = 0;
  double from_ = NAN;
  int threads_ = 0;
};

}  // namespace cgdem::scaling
