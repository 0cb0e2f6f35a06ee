// `cgdem spectrum RUN_DIR [RUN_DIR ...]`: Welch spectra of the cell pressures of one or
// several runs (overlaid), their coherence and their peaks above a red-noise background (spectrum_report.hpp,
// docs/spectra.md).
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "scaling/spectrum_report.hpp"

namespace cgdem::scaling {

class SpectrumCommand {
 public:
  explicit SpectrumCommand(CLI::App& app);  // adds the subcommand and its options to app
  SpectrumCommand(const SpectrumCommand&) = delete;  // CLI11 holds pointers to the members
  SpectrumCommand& operator=(const SpectrumCommand&) = delete;
  bool selected() const { return sub_->parsed(); }
  int run() const;  // after parsing; throws cgdem::Error on bad input

 private:
  CLI::App* sub_;
  std::vector<std::string> runs_, labels_, cells_;
  std::string window_ = "hann", detrend_ = "mean", segment_, output_;
  double overlap_ = 0.5, from_ = 0, to_ = 0, dt_ = 0, confidence_ = 0.95;
  int peaks_ = 3;
  bool no_plot_ = false, pointwise_ = false;
};

}  // namespace cgdem::scaling
