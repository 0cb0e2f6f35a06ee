// The report of a coarse-graining study: REPORT/scale.md (tables of deviations and
// verdicts, observables side by side with the simply-large run, POD spectra and principal
// angles, Welch spectra of the cell pressures overlaid across the runs), a CSV of every
// series and deviation, and PNG plots drawn by plot_scale.py when
// python3 with matplotlib is available (skipped with a note otherwise). Every file is
// written atomically (io/atomic_file.hpp).
#pragma once
#include <string>
#include <vector>

#include "scaling/scale_study.hpp"

namespace cgdem::scaling {

struct ReportContext {
  std::string dir;        // REPORT
  std::string base_case;  // the case file the study derives from
  std::string command;    // the command line, for reproduction
  std::vector<std::string> run_notes;  // "l=2: ran in 4.1 s" / "picked up"
};

// The section "Pressure spectra" of scale.md for runs with pressure cells: the runs'
// Welch spectra of p_A, p_B, p_C overlaid on shared bins, with their deviation from the
// first run (l = 1); writes REPORT/spectrum/ and REPORT/pressure_spectra.csv. Defined and
// documented in spectrum_report.hpp / spectrum_report.cpp. Declared here as well, with
// standard types only, because spectrum_report.hpp cannot be included next to
// scale_study.hpp: series.hpp and spectrum.hpp both define a struct scaling::Peak.
std::string scale_pressure_spectra(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                   double t0, const std::string& report_dir);

// Writes the files; returns the path of scale.md.
std::string write_report(const Study& s, const ReportContext& c);

// Prints the verdict lines ("verdict <run> <group>: agrees|differs (passed/total)").
void print_verdicts(const Study& s);

// Runs plot_scale.py on the report folder; prints a note and returns false when python3 or
// matplotlib is missing or the script fails (never throws).
bool draw_plots(const std::string& report_dir);

namespace detail {
void write_report_csvs(const Study& s, const std::string& dir);  // scale_report_csv.cpp
std::string g10(double v);                                       // %.10g, "nan" when not finite
}  // namespace detail

}  // namespace cgdem::scaling
