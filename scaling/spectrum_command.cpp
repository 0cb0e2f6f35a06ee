#include "scaling/spectrum_command.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "core/error.hpp"

namespace cgdem::scaling {

SpectrumCommand::SpectrumCommand(CLI::App& app)
    : sub_(app.add_subcommand("spectrum", "Welch spectra, coherence and dominant frequencies of the cell pressures "
                                          "(diagnostics.csv) of one or several runs")) {
  sub_->add_option("runs", runs_, "run folder(s) written by cgdem run; several are overlaid")->required();
  sub_->add_option("--window", window_, "segment window: hann or rect")->capture_default_str();
  sub_->add_option("--segment", segment_,
                   "segment length: N samples (e.g. 256) or seconds (e.g. 0.256s); default: the largest power "
                   "of two giving 8 segments");
  sub_->add_option("--overlap", overlap_, "overlap of consecutive segments, fraction in [0, 1)")->capture_default_str();
  sub_->add_option("--detrend", detrend_, "per segment: none, mean or linear")->capture_default_str();
  sub_->add_option("--from", from_, "first time to use, s");
  sub_->add_option("--to", to_, "last time to use, s");
  sub_->add_option("--cells", cells_, "cells to analyse, e.g. A,B,C (default: every p_ column)")->delimiter(',');
  sub_->add_option("--labels", labels_, "one label per run (default: the folder names)")->delimiter(',');
  sub_->add_option("--dt", dt_, "resample linearly onto this interval, s (non-uniform output times, or runs "
                                "written at different intervals)");
  sub_->add_option("--peaks", peaks_, "significant peaks listed per cell, at most")->capture_default_str();
  sub_->add_option("--confidence", confidence_,
                   "level of the red-noise test: a peak must exceed this quantile of AR(1) noise, in (0, 1)")
      ->capture_default_str();
  sub_->add_option("--output", output_, "output folder (default RUN_DIR/spectrum for one run; required for several)");
  sub_->add_flag("--pointwise", pointwise_,
                 "test each bin at --confidence (default: the global level, every bin at confidence^(1/bins))");
  sub_->add_flag("--no-plot", no_plot_, "do not run scaling/plot_spectrum.py");
}

int SpectrumCommand::run() const {
  SpectrumSettings s;
  s.window = parse_window(window_);
  s.detrend = parse_detrend(detrend_);
  s.segment = segment_;
  s.overlap = overlap_;
  if (sub_->count("--from")) s.from = from_;
  if (sub_->count("--to")) s.to = to_;
  if (s.from && s.to && *s.to <= *s.from) throw Error(fmt::format("--from {} s is not before --to {} s", from_, to_));
  if (sub_->count("--dt") && !(dt_ > 0)) throw Error(fmt::format("--dt: {} s is not a positive interval", dt_));
  s.dt = dt_;
  s.cells = cells_;
  s.peaks = peaks_;
  s.confidence = confidence_;
  s.pointwise = pointwise_;
  s.plot = !no_plot_;
  std::string out = output_;
  if (out.empty()) {
    if (runs_.size() > 1) throw Error("--output: several runs are overlaid; give the folder to write into");
    out = (std::filesystem::path(runs_[0]) / "spectrum").string();
  }
  const SpectrumAnalysis a = analyse_runs(runs_, labels_, s);
  std::fputs(dominant_summary(a).c_str(), stdout);
  const std::string note = write_spectrum_outputs(a, out);
  std::printf("%s\nwrote %s/spectrum.md, psd.csv, background.csv, coherence.csv, peaks.csv\n", note.c_str(), out.c_str());
  return 0;
}

}  // namespace cgdem::scaling
