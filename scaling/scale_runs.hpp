// The runs of a coarse-graining study: the same case at several ratios l (same total solid
// mass, geometry and grid), plus optionally the "simply large" system, each in its own
// folder of the report:
//   REPORT/l=<l>/case.toml            [[particles.species]] ratio = l (d_original kept)
//   REPORT/simply_large_<L>/case.toml  ratio = 1, d_original multiplied by L (real
//                                      particles of the coarse parcel's size, no scaling)
// Inserts given by `count` become `solid_volume = count * parcel volume of the base case`,
// so that every run holds the same mass (eq. 4: m = l^3 m_O, N = N_O / l^3). Cases with
// [[particles.file]] cannot be re-scaled and are rejected.
//
// Pick-up: a run folder is reused, not rerun, when its config.resolved.toml equals the
// derived case's resolved configuration (same keys and values after the --set overrides)
// and the run finished: metrics.csv exists, or, from binaries that do not write it yet,
// energy.csv reaches time.end.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace cgdem::scaling {

struct RunPlan {
  std::string label;      // "l=2", "simply_large_3"
  double ratio = 1;       // l of the run's parcels
  double size = 1;        // parcel diameter / the base case's d_original
  bool simply_large = false;
  std::string dir;        // the run folder
  std::string case_file;  // dir/case.toml
};

// Ratios must be >= 1 and distinct, and contain 1 (the reference); simply_large = 0 for
// none, else > 1. Throws cgdem::Error naming --ratios / --simply-large.
std::vector<RunPlan> plan_runs(const std::vector<double>& ratios, double simply_large, const std::string& report_dir);

// Writes r.case_file from the base case (creates r.dir). Throws cgdem::Error naming the key.
void write_derived_case(const std::string& base_case, const RunPlan& r);

// What a study needs to know of its case (read from a derived case with the overrides).
// The case is resolved by app::resolve_case_file, as `cgdem run` resolves it (same path
// handling, same validation and errors), and `resolved` is exactly the configuration the
// run writes to config.resolved.toml. `out` overrides output.dir (empty: the case's).
struct StudyInfo {
  Vec3 lo, hi;  // domain, m
  std::array<bool, 3> periodic{false, false, false};
  double t_start = 0, t_end = 0;  // s
  double d_parcel_max = 0;        // m, largest parcel diameter of the case
  double d_original = 0;          // m, smallest d_original of its species
  bool air = false;
  double air_dx = 0;  // m
  bool die_filling = false;
  std::string resolved;  // the resolved configuration (TOML text)
};
StudyInfo read_study_info(const std::string& case_file, const std::vector<std::string>& sets, const std::string& out);

// Whether r.dir holds a finished run of exactly this configuration; `why` says why not.
bool finished_run(const RunPlan& r, const StudyInfo& info, std::string* why);

// Runs the case in-process (app::run_case_file) unless finished_run; returns true if it ran.
bool run_or_pick_up(const RunPlan& r, const std::vector<std::string>& sets, const StudyInfo& info);

}  // namespace cgdem::scaling
