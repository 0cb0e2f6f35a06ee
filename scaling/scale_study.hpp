// The analysis of a coarse-graining study (`cgdem scale`): budgets, observables and the
// reduced-order comparison of every run against the reference run l = 1, with a verdict per
// quantity against the thresholds (thresholds.hpp). No file output here (scale_report.hpp).
#pragma once
#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

#include "scaling/budgets.hpp"
#include "scaling/observables.hpp"
#include "scaling/scale_runs.hpp"
#include "scaling/thresholds.hpp"

namespace cgdem::scaling {

struct ObservableRow {
  std::string run, name;
  std::string metric;  // "relative", "time / span", "normalized L2"
  double value = 0, reference = 0, deviation = 0, threshold = 0;
  bool agrees = false;
};

struct PodField {
  std::string field;  // "solid_fraction", "pressure"
  std::string source;  // where the field came from
  int cells = 0, snapshots = 0, modes = 0;  // modes compared (r)
  std::vector<std::string> runs;
  std::vector<Eigen::VectorXd> fraction;    // lambda_k / total per run
  std::vector<Eigen::VectorXd> angles_deg;  // against the reference, per run
  std::vector<double> spectrum_dev;         // max_k<=r |fraction_l - fraction_1|
  std::vector<bool> agrees;
};

struct GroupVerdict {
  std::string run, group;
  int passed = 0, total = 0;
  bool agrees() const { return passed == total; }
};

struct Study {
  std::vector<RunPlan> runs;  // runs[0] is l = 1
  StudyInfo info;             // of the reference case
  double t0 = 0;              // s, analysis start (series, peaks and snapshots from t0 on)
  Thresholds thresholds;
  std::vector<Budget> budgets;
  BudgetScales scales;
  std::vector<BudgetComparison> budget;  // per run
  std::map<std::string, std::map<std::string, bool>> budget_agrees;  // run -> quantity -> verdict
  std::vector<RunObservables> observables;
  std::vector<ObservableRow> observable_rows;
  ProfileSpec profile;
  std::vector<PodField> pod;
  std::vector<GroupVerdict> verdicts;
};

struct PodOptions {
  double dx = 0;            // m, grid of the solid fraction without air (0: 2 x largest parcel)
  double energy = 0.9;      // leading modes: the smallest r holding this share of l = 1's energy
  int max_modes = 5;        // cap on r
};

// Reads every run's outputs from t0 on and compares them. Throws cgdem::Error naming a
// missing file.
Study analyse_study(const std::vector<RunPlan>& runs, const StudyInfo& info, double t0, const Thresholds& th,
                    const PodOptions& pod);

}  // namespace cgdem::scaling
