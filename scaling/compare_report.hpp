// The files of `cgdem compare` (compare_study.hpp), all in one folder, each written
// atomically:
//
//   compare.md            the report: runs (folder, label, revision, case), the resolved
//                         configuration keys that differ, every metric side by side with its
//                         difference from the first run, the curves at the sampled times and
//                         their distances from the first run's curves, the plots
//   metrics_compare.csv   metric,unit,<label>...,diff:<label>...,rel_diff:<label>... (runs
//                         after the first); an empty field is a missing value (NaN, or not
//                         written by the run)
//   curves_compare.csv    t_s,<label>:<column>_<unit>,... at the sampled times (units in the
//                         names: t_s, mass_in_die_kg, transfer_rate_kg_s, p_A_Pa ...)
//   curves_distance.csv   curve,unit,run,normalized_l2,max_abs_diff,t_max_abs_diff_s,samples:
//                         each run after the first against the first
//   runs_compare.csv      label,folder,revision,case (what plot_compare.py reads the full
//                         curves from)
//   curves.png, curves_extra.png  overlaid curves (scaling/plot_compare.py, when python3 has
//                         matplotlib; otherwise the report says the plots were skipped)
//
// Numbers in the CSV files: the shortest text that reads back to the same double.
#pragma once
#include <string>

#include "scaling/compare_study.hpp"

namespace cgdem::scaling {

struct CompareOutput {
  std::string dir;
  std::string command;  // the command line, quoted in the report
  bool plot = true;
};

// Writes the files; returns "" when the plots were drawn, else why not.
std::string write_compare_outputs(const Comparison& c, const CompareOutput& o);

// The Markdown report alone (plot_note: "" when curves.png / curves_extra.png exist).
std::string compare_markdown(const Comparison& c, const CompareOutput& o, const std::string& plot_note);

}  // namespace cgdem::scaling
