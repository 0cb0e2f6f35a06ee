#include "scaling/compare_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/atomic_file.hpp"
#include "io/metrics.hpp"
#include "scaling/plot_script.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

namespace {

const char* const kMissing = "—";

// Shortest text that reads back to the same double (0.06, not 0.059999999999999998).
std::string csv_num(double v) { return std::isfinite(v) ? fmt::format("{}", v) : ""; }
std::string md_num(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : kMissing; }
std::string md_diff(double v) { return v == 0 ? "0" : std::isfinite(v) ? fmt::format("{:+.4g}", v) : kMissing; }
std::string md_pct(double v) {
  return v == 0 ? "0 %" : std::isfinite(v) ? fmt::format("{:+.3g} %", 100 * v) : kMissing;
}

// A CSV field: quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

// Text for a Markdown table cell.
std::string md_cell(const std::string& s) {
  std::string out;
  for (char ch : s) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

std::string unit_or_dash(const std::string& u) { return u.empty() ? kMissing : u; }

std::string header_comment(const Comparison& c) {
  std::vector<std::string> runs;
  for (const auto& r : c.runs) runs.push_back(fmt::format("{}={}", r.label, r.dir));
  return fmt::format("# cgdem {} compare: {}; reference {}\n", kGitRevision, fmt::join(runs, "; "), c.runs[0].label);
}

// Curves drawn in curves.png; the others go to curves_extra.png (plot_compare.py, same rule).
bool main_curve(const std::string& column) {
  return column == "mass_in_die" || column == "transfer_rate" || column.rfind("p_", 0) == 0;
}

// Whether curves.png (main = true) or curves_extra.png (main = false) has a panel.
bool has_panels(const Curves& k, bool main) {
  for (const auto& cv : k.curves)
    if (main_curve(cv.column) == main) return true;
  return false;
}

// ",v[from],...,v[last]" (an empty field for a missing value).
std::string csv_tail(const std::vector<double>& v, size_t from = 0) {
  std::string s;
  for (size_t i = from; i < v.size(); ++i) s += fmt::format(",{}", csv_num(v[i]));
  return s;
}

// ",<prefix><label><suffix>" for each run from `from` on.
std::string label_columns(const Comparison& c, const std::string& prefix, const std::string& suffix, size_t from = 0) {
  std::string s;
  for (size_t i = from; i < c.runs.size(); ++i) s += fmt::format(",{}{}{}", prefix, c.runs[i].label, suffix);
  return s;
}

std::string metrics_csv(const Comparison& c) {
  std::string s = header_comment(c) +
                  fmt::format(
                      "# diff = value - value of {0}; rel_diff = diff / |value of {0}|; an empty field: missing, "
                      "i.e. not computed (the run did not write the metric: e.g. pressures without air) or NaN\n",
                      c.runs[0].label);
  s += fmt::format("metric,unit{}{}{}\n", label_columns(c, "", ""), label_columns(c, "diff:", "", 1),
                   label_columns(c, "rel_diff:", "", 1));
  for (const auto& m : c.metrics)
    s += fmt::format("{},{}{}{}{}\n", m.name, m.unit, csv_tail(m.value), csv_tail(m.abs_diff, 1),
                     csv_tail(m.rel_diff, 1));
  return s;
}

std::string curves_csv(const Comparison& c) {
  const Curves& k = c.curves;
  std::string s = header_comment(c) + fmt::format(
                                          "# common range {} to {} s, sampled every {:g} s by linear interpolation; an "
                                          "empty field: missing\nt_s",
                                          k.t_lo, k.t_hi, k.dt);
  for (const auto& cv : k.curves) s += label_columns(c, "", fmt::format(":{}", column_with_unit(cv.column)));
  s += '\n';
  for (size_t j = 0; j < k.times.size(); ++j) {
    std::vector<double> row;  // every curve of every run at t_j
    for (const auto& cv : k.curves)
      for (const auto& y : cv.sampled) row.push_back(y[j]);
    s += csv_num(k.times[j]) + csv_tail(row) + "\n";
  }
  return s;
}

std::string distance_csv(const Comparison& c) {
  const Curves& k = c.curves;
  std::string s =
      header_comment(c) + fmt::format(
                              "# common range {} to {} s; on the {} samples of {} in it, trapezoid weights w: "
                              "normalized_l2 = sqrt(sum w (y - y_ref)^2 / sum w y_ref^2), y_ref the curve of {}; "
                              "max_abs_diff = max |y - y_ref| in the curve's unit; samples where both are finite\n",
                              k.t_lo, k.t_hi, k.reference_points, c.runs[0].label, c.runs[0].label);
  s += "curve,unit,run,normalized_l2,max_abs_diff,t_max_abs_diff_s,samples\n";
  for (const auto& cv : k.curves)
    for (size_t i = 1; i < c.runs.size(); ++i)
      s += fmt::format("{},{},{},{},{},{},{}\n", cv.column, cv.unit, c.runs[i].label, csv_num(cv.l2[i]),
                       csv_num(cv.max_abs[i]), csv_num(cv.t_max_abs[i]), cv.points[i]);
  return s;
}

std::string runs_csv(const Comparison& c) {
  std::string s = header_comment(c) + "label,folder,revision,case\n";
  for (const auto& r : c.runs)
    s += fmt::format("{},{},{},{}\n", csv_field(r.label), csv_field(fs::absolute(r.dir).lexically_normal().string()),
                     csv_field(r.revision), csv_field(r.case_file));
  return s;
}

// "| a | b |\n|---|---|\n" for the given header cells.
std::string table_head(const std::vector<std::string>& cells) {
  std::string s = "|", rule = "|";
  for (const auto& h : cells) s += " " + h + " |", rule += "---|";
  return s + "\n" + rule + "\n";
}

std::string runs_section(const Comparison& c) {
  std::string md = "## Runs\n\n" + table_head({"", "label", "folder", "git revision", "case"});
  for (size_t i = 0; i < c.runs.size(); ++i) {
    const auto& r = c.runs[i];
    md += fmt::format("| {}{} | {} | `{}` | {} | {} |\n", i + 1, i == 0 ? " (reference)" : "", md_cell(r.label),
                      md_cell(r.dir), r.revision.empty() ? kMissing : md_cell(r.revision),
                      r.case_file.empty() ? kMissing : fmt::format("`{}`", md_cell(r.case_file)));
  }
  md += "\n### Configuration differences\n\n";
  std::vector<std::string> without;
  for (const auto& r : c.runs)
    if (!r.has_config) without.push_back(fmt::format("`{}`", r.dir));
  if (!without.empty()) md += fmt::format("No config.resolved.toml in {}: not compared.\n\n", fmt::join(without, ", "));
  if (c.runs.size() - without.size() < 2) return md;
  if (c.config.empty())
    return md + "The resolved configurations (config.resolved.toml) hold the same keys and values.\n\n";
  md += fmt::format("{} resolved key(s) differ (config.resolved.toml; {}: the run has no such key):\n\n",
                    c.config.size(), kMissing);
  std::vector<std::string> head{"key"};
  for (const auto& r : c.runs) head.push_back(md_cell(r.label));
  md += table_head(head);
  for (const auto& d : c.config) {
    md += "| `" + md_cell(d.key) + "` |";
    for (const auto& v : d.values) md += fmt::format(" {} |", v ? md_cell(*v) : kMissing);
    md += "\n";
  }
  return md + "\n";
}

std::string metrics_section(const Comparison& c) {
  const std::string ref = md_cell(c.runs[0].label);
  std::string md = fmt::format(
      "## Metrics (metrics.csv)\n\nΔ = value − value of {0}; relative = Δ / |value of {0}|. \"not computed\": the run "
      "did not write the metric (cgdem run leaves out what it cannot compute, e.g. the pressures of a run without "
      "air); {1}: NaN, or a difference with a value that is missing (a relative difference from 0 is missing too).\n\n",
      ref, kMissing);
  std::vector<std::string> head{"metric", "unit"};
  for (const auto& r : c.runs) head.push_back(md_cell(r.label));
  for (size_t i = 1; i < c.runs.size(); ++i) {
    head.push_back("Δ " + md_cell(c.runs[i].label));
    head.push_back("relative " + md_cell(c.runs[i].label));
  }
  md += table_head(head);
  for (const auto& m : c.metrics) {
    md += fmt::format("| {} | {} |", m.name, unit_or_dash(m.unit));
    for (size_t i = 0; i < c.runs.size(); ++i)
      md += fmt::format(" {} |", io::has_metric(c.runs[i].metrics, m.name) ? md_num(m.value[i]) : "not computed");
    for (size_t i = 1; i < c.runs.size(); ++i)
      md += fmt::format(" {} | {} |", md_diff(m.abs_diff[i]), md_pct(m.rel_diff[i]));
    md += "\n";
  }
  return md + "\n";
}

std::string curves_section(const Comparison& c, const std::string& plot_note) {
  const Curves& k = c.curves;
  const std::string ref = md_cell(c.runs[0].label);
  std::string md = fmt::format(
      "## Curves (diagnostics.csv)\n\nCommon time range t = {:g} to {:g} s (the span every run's diagnostics.csv "
      "covers); values linearly interpolated every {:g} s.\n\n",
      k.t_lo, k.t_hi, k.dt);
  md += fmt::format(
      "Distance from {0}'s curve y_ref over the common range, on {0}'s own {1} samples in it (trapezoid weights): "
      "**normalised L2** = sqrt(∫ (y − y_ref)² dt / ∫ y_ref² dt), i.e. the L2 norm of the difference divided by the L2 "
      "norm of {0}'s curve (0: the same curve, 1: a difference as large as the curve itself); **max |Δ|** in the "
      "curve's unit. Samples where either value is NaN are left out; {2}: no sample finite in both, or {0}'s curve "
      "is zero.\n\n",
      ref, k.reference_points, kMissing);
  std::vector<std::string> head{"curve", "unit", "run", "normalised L2", "max abs Δ", "at t (s)", "samples"};
  md += table_head(head);
  for (const auto& cv : k.curves)
    for (size_t i = 1; i < c.runs.size(); ++i)
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", cv.column, unit_or_dash(cv.unit),
                        md_cell(c.runs[i].label), md_num(cv.l2[i]), md_num(cv.max_abs[i]), md_num(cv.t_max_abs[i]),
                        cv.points[i]);
  if (!k.no_values.empty())
    md += fmt::format("\nNo finite value in any run (left out): {}.\n", fmt::join(k.no_values, ", "));
  if (plot_note.empty()) {
    if (has_panels(k, true)) md += "\n![mass in the die, transfer rate, cell pressures](curves.png)\n";
    if (has_panels(k, false)) md += "\n![the other columns](curves_extra.png)\n";
  } else
    md += fmt::format("\nPlots skipped: {}. Every curve is in curves_compare.csv.\n", plot_note);
  for (const auto& cv : k.curves) {
    md += fmt::format("\n### {}{}\n\n", cv.column, cv.unit.empty() ? "" : " (" + cv.unit + ")");
    std::vector<std::string> h{"t (s)"};
    for (const auto& r : c.runs) h.push_back(md_cell(r.label));
    for (size_t i = 1; i < c.runs.size(); ++i) h.push_back("Δ " + md_cell(c.runs[i].label));
    md += table_head(h);
    for (size_t j = 0; j < k.times.size(); ++j) {
      md += fmt::format("| {:g} |", k.times[j]);
      for (const auto& y : cv.sampled) md += fmt::format(" {} |", md_num(y[j]));
      for (size_t i = 1; i < c.runs.size(); ++i)
        md += fmt::format(" {} |", md_diff(cv.sampled[i][j] - cv.sampled[0][j]));
      md += "\n";
    }
  }
  return md;
}

}  // namespace

std::string compare_markdown(const Comparison& c, const CompareOutput& o, const std::string& plot_note) {
  std::string md = fmt::format("# Comparison of runs\n\ncgdem {}: `{}`. Reference: the first run, {}.\n\n",
                               kGitRevision, md_cell(o.command), md_cell(c.runs[0].label));
  md += runs_section(c) + metrics_section(c) + curves_section(c, plot_note);
  md += "\nFiles: `metrics_compare.csv`, `curves_compare.csv`, `curves_distance.csv`, `runs_compare.csv`";
  if (plot_note.empty() && has_panels(c.curves, true)) md += ", `curves.png`";
  if (plot_note.empty() && has_panels(c.curves, false)) md += ", `curves_extra.png`";
  md += ".\n";
  return md;
}

std::string write_compare_outputs(const Comparison& c, const CompareOutput& o) {
  std::error_code ec;
  fs::create_directories(o.dir, ec);
  if (ec) throw Error(fmt::format("--output: cannot create '{}': {}", o.dir, ec.message()));
  const auto path = [&](const char* name) { return (fs::path(o.dir) / name).string(); };
  io::write_file_atomic(path("metrics_compare.csv"), metrics_csv(c));
  io::write_file_atomic(path("curves_compare.csv"), curves_csv(c));
  io::write_file_atomic(path("curves_distance.csv"), distance_csv(c));
  io::write_file_atomic(path("runs_compare.csv"), runs_csv(c));
  const std::string note = o.plot ? run_plot_script("plot_compare.py", o.dir) : "switched off (--no-plot)";
  io::write_file_atomic(path("compare.md"), compare_markdown(c, o, note));
  return note;
}

}  // namespace cgdem::scaling
