#include "scaling/compare_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scaling/compare_report.hpp"
#include "scaling/compare_study.hpp"

namespace cgdem::scaling {

struct CompareCommand::Options {
  std::vector<std::string> runs, labels;
  std::string output;
  double dt = 0.02, from = 0, to = 0;
  bool no_plot = false;
};

CompareCommand::~CompareCommand() = default;

CompareCommand::CompareCommand(CLI::App& app)
    : sub_(app.add_subcommand("compare",
                              "finished runs side by side against the first: configuration differences, "
                              "metrics, diagnostics curves and their distances (e.g. with air / vacuum)")),
      o_(std::make_unique<Options>()) {
  sub_->add_option("runs", o_->runs, "run folders written by cgdem run (at least two; the first is the reference)")
      ->required();
  sub_->add_option("--labels", o_->labels, "one label per run (default: the folder names)")->delimiter(',');
  sub_->add_option("--output", o_->output, "report folder (default: compare_<RUN_A name>_<RUN_B name>)");
  sub_->add_option("--dt", o_->dt, "interval of the sampled curve tables, s (the L2 distances use every sample)")
      ->capture_default_str();
  sub_->add_option("--from", o_->from, "start of the compared time range, s (default: the common range's)");
  sub_->add_option("--to", o_->to, "end of the compared time range, s (default: the common range's)");
  sub_->add_flag("--no-plot", o_->no_plot, "do not run scaling/plot_compare.py");
}

int CompareCommand::run() const {
  CurveSettings s;
  s.dt = o_->dt;
  if (sub_->count("--from")) s.from = o_->from;
  if (sub_->count("--to")) s.to = o_->to;
  if (s.from && s.to && *s.to <= *s.from)
    throw Error(fmt::format("--from {} s is not before --to {} s", o_->from, o_->to));
  const Comparison c = compare_runs(o_->runs, o_->labels, s);
  CompareOutput out;
  out.dir = o_->output;
  if (out.dir.empty()) out.dir = fmt::format("compare_{}_{}", folder_name(o_->runs[0]), folder_name(o_->runs[1]));
  // The command as given, for the report.
  out.command = fmt::format("cgdem compare {}", fmt::join(o_->runs, " "));
  if (!o_->labels.empty()) out.command += fmt::format(" --labels {}", fmt::join(o_->labels, ","));
  if (!o_->output.empty()) out.command += fmt::format(" --output {}", o_->output);
  if (sub_->count("--dt")) out.command += fmt::format(" --dt {:g}", o_->dt);
  if (s.from) out.command += fmt::format(" --from {:g}", *s.from);
  if (s.to) out.command += fmt::format(" --to {:g}", *s.to);
  out.plot = !o_->no_plot;
  const std::string ref = c.runs[0].label;
  fmt::print("compare: reference {} ({}); common range {:g} to {:g} s\n", ref, c.runs[0].dir, c.curves.t_lo,
             c.curves.t_hi);
  for (const auto& d : c.config) {
    std::string values;
    for (size_t i = 0; i < d.values.size(); ++i)
      values += fmt::format("{}{}={}", i ? ", " : "", c.runs[i].label, d.values[i].value_or("(absent)"));
    fmt::print("config {}: {}\n", d.key, values);
  }
  for (const auto& cv : c.curves.curves)
    for (size_t i = 1; i < c.runs.size(); ++i)
      fmt::print("curve {} {}: normalised L2 {}\n", cv.column, c.runs[i].label,
                 std::isfinite(cv.l2[i]) ? fmt::format("{:.4g}", cv.l2[i]) : "missing");
  const std::string note = write_compare_outputs(c, out);
  if (!note.empty()) fmt::print("compare: plots skipped: {}\n", note);
  fmt::print("wrote {}/compare.md, metrics_compare.csv, curves_compare.csv, curves_distance.csv{}\n", out.dir,
             note.empty() ? ", curves.png" : "");
  return 0;
}

}  // namespace cgdem::scaling
