#include "scaling/scale_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "scaling/plot_script.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;
using detail::g10;

namespace {

std::string num(double v, int digits = 3) { return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : "n/a"; }
const char* word(bool ok) { return ok ? "agrees" : "**differs**"; }

std::string runs_table(const Study& s, const ReportContext& c) {
  std::string t = "| run | ratio l | parcel diameter (m) | parcels | solid mass (kg) | run |\n|---|---|---|---|---|---|\n";
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const auto& p = s.runs[r];
    t += fmt::format("| {} | {:g} | {} | {} | {} | {} |\n", p.label, p.ratio, num(p.size * s.info.d_original, 4),
                     s.budgets[r].particles, num(s.budgets[r].mass, 5), r < c.run_notes.size() ? c.run_notes[r] : "");
  }
  return t;
}

std::string budget_section(const Study& s) {
  std::string t = fmt::format(
      "## Energy and momentum per unit solid mass\n\n"
      "Series per unit solid mass M (J/kg, m/s) on the reference run's output times; deviation "
      "D = max over t of |q_l - q_1| / S with the energy scale S_E = {} J/kg (the largest energy exchanged per "
      "unit mass at l = 1), the velocity scale sqrt(2 S_E) = {} m/s, and for the rotational energies their own "
      "peak at l = 1. The closure (E_balance(t) - E_balance(t0)) / M is judged against zero for every run. "
      "Cells: D (time of the maximum, s).\n\n| quantity | unit | scale | threshold |",
      num(s.scales.energy, 4), num(s.scales.velocity, 4));
  for (const auto& r : s.runs) t += " " + r.label + " |";
  t += "\n|---|---|---|---|";
  for (size_t r = 0; r < s.runs.size(); ++r) t += "---|";
  t += "\n";
  for (const auto& q : budget_quantities()) {
    t += fmt::format("| {} | {} | {} | {:g} |", q, budget_unit(q), num(q == "closure" ? s.scales.energy : s.scales.of(q)),
                     s.thresholds[budget_threshold(q)]);
    for (const auto& c : s.budget) {
      const auto& ag = s.budget_agrees.at(c.label);
      if (!ag.count(q)) {
        t += " (reference) |";
        continue;
      }
      t += fmt::format(" {} ({}) {} |", num(c.max_dev.at(q)), num(c.t_max_dev.at(q)), word(ag.at(q)));
    }
    t += "\n";
  }
  // The rotational energy of the parcel and of the originals it stands for.
  t += "\n### Rotational energy: the parcel's own and that of its l^3 originals\n\n"
       "A parcel has I = l^5 I_O (eq. 5); the l^3 originals it stands for, each spinning at the parcel's w, hold "
       "l^3 I_O w^2 / 2 = (I w^2 / 2) / l^2. A parcel rolling at speed v has w = 2 v / (l d_O), so its own "
       "e_rot = v^2 / 5 per unit mass whatever l, while the originals' e_rot_orig = v^2 / (5 l^2). Time means of "
       "the ratio to l = 1 (where the reference exceeds 5 % of its peak):\n\n"
       "| run | l | e_rot / e_rot(l=1) | e_rot_orig / e_rot_orig(l=1) | predicted: (e_rot ratio) / l^2 | "
       "e_trans / e_trans(l=1) |\n|---|---|---|---|---|---|\n";
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const auto& c = s.budget[r];
    const double l = s.runs[r].ratio;
    t += fmt::format("| {} | {:g} | {} | {} | {} | {} |\n", c.label, l, num(c.mean_ratio.at("e_rot")),
                     num(c.mean_ratio.at("e_rot_orig")), num(c.mean_ratio.at("e_rot") / (l * l)),
                     num(c.mean_ratio.at("e_trans")));
  }
  for (const auto& b : s.budgets)
    if (b.rot_orig_derived)
      t += fmt::format("\n{}: energy.csv has no E_kin_rot_orig column (written before it existed); e_rot / l^2 "
                       "is shown instead.\n", b.label);
  return t + "\n";
}

std::string observables_section(const Study& s) {
  std::string t = "## Observables\n\n"
                  "Values side by side (SI units; positions from the domain's lower corner, profile columns "
                  "of " + num(s.profile.bin) + " m; \"not computed\": the run has no such value, e.g. the pressures "
                  "of a run without air):\n\n| observable |";
  for (const auto& r : s.runs) t += " " + r.label + " |";
  t += "\n|---|";
  for (size_t r = 0; r < s.runs.size(); ++r) t += "---|";
  t += "\n";
  for (const auto& [name, v1] : s.observables[0].scalars) {
    t += "| " + name + " |";
    for (const auto& o : s.observables)
      t += " " + (o.scalars.count(name) ? num(o.scalars.at(name), 4) : std::string("not computed")) + " |";
    t += "\n";
  }
  t += "\nDeviation from l = 1 and verdict:\n\n| run | observable | metric | deviation | threshold | verdict |\n"
       "|---|---|---|---|---|---|\n";
  for (const auto& r : s.observable_rows)
    t += fmt::format("| {} | {} | {} | {} | {:g} | {} |\n", r.run, r.name, r.metric, num(r.deviation), r.threshold,
                     word(r.agrees));
  return t + "\n";
}

std::string pod_section(const Study& s) {
  std::string t = "## Reduced-order comparison (POD)\n\n"
                  "Method of snapshots on the fluctuation about the temporal mean (scaling/pod.hpp): modal energy "
                  "fractions lambda_k / sum lambda, and the principal angles between the span of the leading r modes "
                  "of l = 1 and of each run (r: the modes holding 90 % of l = 1's energy, at most 5).\n\n";
  if (s.pod.empty()) t += "No field had three or more snapshot times shared by every run: skipped.\n\n";
  for (const auto& p : s.pod) {
    t += fmt::format("### {}\n\nFrom {}; {} cells, {} snapshots, r = {}.\n\n| mode |", p.field, p.source, p.cells,
                     p.snapshots, p.modes);
    for (const auto& r : p.runs) t += " " + r + " |";
    t += "\n|---|";
    for (size_t r = 0; r < p.runs.size(); ++r) t += "---|";
    t += "\n";
    for (long k = 0; k < 8; ++k) {
      t += fmt::format("| {} |", k + 1);
      for (const auto& f : p.fraction) t += " " + (k < f.size() ? num(f(k)) : "-") + " |";
      t += "\n";
    }
    t += "\n| run | principal angles (deg) | spectrum deviation | verdict |\n|---|---|---|---|\n";
    for (size_t r = 1; r < p.runs.size(); ++r) {
      std::string a;
      for (long i = 0; i < p.angles_deg[r].size(); ++i) a += (i ? ", " : "") + num(p.angles_deg[r](i));
      t += fmt::format("| {} | {} | {} | {} |\n", p.runs[r], a, num(p.spectrum_dev[r]), word(p.agrees[r]));
    }
    t += "\n";
  }
  return t;
}

// "## Pressure spectra": not applicable without air or pressure cells, else the runs'
// Welch spectra overlaid (scale_pressure_spectra, spectrum_report.cpp).
std::string pressure_spectra_md(const Study& s, const std::string& report_dir) {
  std::string none;
  if (!s.info.air) none = "the case has no air, so there is no pressure to analyse";
  else if (!s.info.die_filling)
    none = "the case has no pressure cells (only [walls.die_filling] writes p_<cell> to diagnostics.csv)";
  if (!none.empty()) {
    fmt::print("spectrum: not applicable: {}\n", none);
    return "## Pressure spectra\n\nNot applicable: " + none + ".\n\n";
  }
  std::vector<std::string> dirs, labels;
  for (const auto& r : s.runs) dirs.push_back(r.dir), labels.push_back(r.label);
  return scale_pressure_spectra(dirs, labels, s.t0, report_dir);
}

}  // namespace

std::string write_report(const Study& s, const ReportContext& c) {
  detail::write_report_csvs(s, c.dir);
  std::string md = fmt::format("# Coarse-graining consistency: {}\n\n`{}`\n\n", c.base_case, c.command);
  md += runs_table(s, c);
  md += fmt::format("\nAnalysis from t0 = {:g} s (`--from`): budgets count from t0; curves, peaks and snapshots are "
                    "taken from t0 on.\n", s.t0);
  md += "\n## Thresholds\n\n| name | value | meaning |\n|---|---|---|\n";
  for (const auto& d : default_thresholds())
    md += fmt::format("| {} | {:g} | {} |\n", d.name, s.thresholds[d.name], d.meaning);
  md += "\n## Verdicts\n\nl = 2, 3 should agree with l = 1; the simply-large run is shown next to them (the method "
        "claims it does not agree where the air's drag matters: in vacuum only its contact time differs). Groups: "
        "budgets (energies except rotation, momentum, closure), rotation (the parcels' own rotational energy), "
        "observables, pod_<field>; e_rot_orig is shown but not judged (it differs by l^2 by construction).\n\n"
        "| run | group | within threshold | verdict |\n|---|---|---|---|\n";
  for (const auto& v : s.verdicts)
    md += fmt::format("| {} | {} | {}/{} | {} |\n", v.run, v.group, v.passed, v.total, word(v.agrees()));
  md += "\n" + budget_section(s) + observables_section(s) + pod_section(s);
  md += pressure_spectra_md(s, c.dir);
  md += "## Files\n\nbudget_<run>.csv and deviation_<run>.csv (series per unit mass and (q_l - q_1)/S on the common "
        "times), budget_summary.csv, observables.csv, profile.csv, curves.csv (die filling), "
        "pod_<field>_spectrum.csv, pod_<field>_angles.csv, pressure_spectra.csv and spectrum/ (with air and pressure "
        "cells), the runs in <run>/ with their derived case.toml; plots "
        "*.png when matplotlib is available (scaling/plot_scale.py).\n";
  const std::string path = (fs::path(c.dir) / "scale.md").string();
  io::write_file_atomic(path, md);
  return path;
}

void print_verdicts(const Study& s) {
  fmt::print("energy scale S_E = {:.4g} J/kg, velocity scale {:.4g} m/s\n", s.scales.energy, s.scales.velocity);
  for (const auto& c : s.budget) {
    std::string line;
    for (const auto& q : budget_quantities())
      if (s.budget_agrees.at(c.label).count(q)) line += fmt::format(" {}={:.3g}", q, c.max_dev.at(q));
    fmt::print("deviation {}:{}\n", c.label, line);
  }
  for (const auto& r : s.observable_rows)
    fmt::print("observable {} {}: {:.3g} ({}, threshold {:g}) {}\n", r.run, r.name, r.deviation, r.metric, r.threshold,
               r.agrees ? "agrees" : "differs");
  for (const auto& p : s.pod)
    for (size_t r = 1; r < p.runs.size(); ++r)
      fmt::print("pod {} {}: largest angle {:.3g} deg, spectrum deviation {:.3g} (r = {})\n", p.field, p.runs[r],
                 p.angles_deg[r].size() ? p.angles_deg[r].maxCoeff() : NAN, p.spectrum_dev[r], p.modes);
  for (const auto& v : s.verdicts)
    fmt::print("verdict {} {}: {} ({}/{})\n", v.run, v.group, v.agrees() ? "agrees" : "differs", v.passed, v.total);
}

bool draw_plots(const std::string& report_dir) {
  const std::string why = run_plot_script("plot_scale.py", report_dir);
  if (!why.empty())
    fmt::print("cgdem scale: plots skipped ({}); the report and CSV files hold every series\n", why);
  return why.empty();
}

}  // namespace cgdem::scaling
