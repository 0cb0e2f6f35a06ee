#include "scaling/scale_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "core/error.hpp"
#include "io/particle_h5.hpp"
#include "scaling/fields.hpp"
#include "scaling/pod.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

namespace {

// Scalars: event times against the run span, everything else relative to l = 1.
void compare_scalars(Study& s) {
  const auto& ref = s.observables[0].scalars;
  const double span = s.info.t_end - s.info.t_start;
  for (size_t r = 1; r < s.runs.size(); ++r)
    for (const auto& [name, v1] : ref) {
      const auto& sc = s.observables[r].scalars;
      // Not observables of the flow: bookkeeping (the parcel count differs by l^3 by design)
      // and the final kinetic energy (the budget section compares it over time).
      static const std::set<std::string> skip{"end_time_s", "particles", "removed", "E_kin_trans_J", "com_y_m"};
      if (!sc.count(name) || skip.count(name)) continue;
      ObservableRow row{s.runs[r].label, name, "", sc.at(name), v1, 0, 0, false};
      const bool is_time = name.size() > 7 && name.substr(name.size() - 7) == "_time_s";
      if (is_time) {
        row.metric = "time / span";
        row.deviation = std::fabs(row.value - v1) / span;
        row.threshold = s.thresholds["time"];
      } else {
        row.metric = "relative";
        row.deviation = std::fabs(row.value - v1) / std::max(std::fabs(v1), 1e-300);
        row.threshold = s.thresholds["scalar"];
      }
      row.agrees = row.deviation <= row.threshold;
      s.observable_rows.push_back(row);
    }
}

void compare_curve(Study& s, const std::string& name, const Series& ref, size_t r, const Series& c) {
  if (ref.t.size() < 2 || c.t.size() < 2) return;
  const auto t = common_times(ref.t, {ref, c});
  if (t.size() < 2) return;
  const auto a = resample(c, t), b = resample(ref, t);
  ObservableRow row{s.runs[r].label, name, "normalized L2", NAN, NAN, normalized_l2(t, a, b), s.thresholds["curve"],
                    false};
  row.agrees = row.deviation <= row.threshold;
  s.observable_rows.push_back(row);
}

void compare_profiles(Study& s) {
  const auto& x = s.observables[0].profile_x;
  const auto& h1 = s.observables[0].profile_h;
  for (size_t r = 1; r < s.runs.size(); ++r) {
    const auto& h = s.observables[r].profile_h;
    if (h.size() != h1.size()) continue;
    std::vector<double> t(x.begin(), x.end());  // uniform bins: trapezoid weights on x
    ObservableRow row{s.runs[r].label, "pile_height_profile", "normalized L2", NAN, NAN, normalized_l2(t, h, h1),
                      s.thresholds["profile"], false};
    row.agrees = row.deviation <= row.threshold;
    s.observable_rows.push_back(row);
  }
}

// Snapshot matrix of one field of one run at the given times (columns).
Eigen::MatrixXd field_matrix(const RunPlan& run, const std::vector<Frame>& frames, const std::string& field,
                             const std::vector<double>& times, const Grid& g, bool from_air, double tol) {
  Eigen::MatrixXd X(g.cells(), static_cast<Eigen::Index>(times.size()));
  for (size_t j = 0; j < times.size(); ++j) {
    auto it = std::find_if(frames.begin(), frames.end(), [&](const Frame& f) { return std::fabs(f.t - times[j]) <= tol; });
    if (it == frames.end()) throw Error(fmt::format("{}: no snapshot at t = {:g} s", run.dir, times[j]));
    std::vector<double> v;
    if (from_air) {
      Grid gg;
      v = read_cell_field(it->file, field == "pressure" ? "p" : "eps", &gg);
      if (gg.cells() != g.cells()) throw Error(fmt::format("{}: grid differs from the reference run's", it->file));
      if (field == "solid_fraction")
        for (double& e : v) e = 1 - e;
    } else {
      v = solid_fraction(io::read_particles_h5(it->file), g);
    }
    X.col(static_cast<Eigen::Index>(j)) = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }
  return X;
}

// The snapshot times of the first run (from t0 on) that every run has, within tol.
std::vector<double> shared_times(const std::vector<std::vector<Frame>>& frames, size_t runs, double t0, double tol) {
  std::vector<double> times;
  for (const auto& f : frames[0]) {
    if (f.t < t0 - tol) continue;
    bool everywhere = true;
    for (size_t r = 1; r < runs && everywhere; ++r)
      everywhere = std::any_of(frames[r].begin(), frames[r].end(),
                               [&](const Frame& x) { return std::fabs(x.t - f.t) <= tol; });
    if (everywhere) times.push_back(f.t);
  }
  return times;
}

// The cells of the POD: the air grid of the first snapshot, or (in vacuum) cells of --pod-dx
// (default twice the largest parcel diameter) over the domain.
Grid pod_grid(const Study& s, const std::vector<std::vector<Frame>>& frames, bool from_air, const PodOptions& o) {
  Grid g;
  if (from_air) {
    read_cell_field(frames[0].front().file, "eps", &g);
  } else {
    double dmax = 0;
    for (const auto& r : s.runs) dmax = std::max(dmax, r.size * s.info.d_original);
    g = grid_over(s.info.lo, s.info.hi, o.dx > 0 ? o.dx : 2 * dmax, s.info.periodic);
  }
  return g;
}

void pod_field(Study& s, const std::string& field, const PodOptions& o) {
  const bool from_air = s.info.air;
  const std::string prefix = from_air ? "air" : "particles";
  const double span = s.info.t_end - s.info.t_start, tol = 1e-6 * span;
  // Snapshot times present in every run.
  std::vector<std::vector<Frame>> frames;
  for (const auto& r : s.runs) frames.push_back(list_frames(r.dir, prefix));
  const std::vector<double> times = shared_times(frames, s.runs.size(), s.t0, tol);
  if (times.size() < 3) {
    fmt::print("cgdem scale: POD of {} skipped: only {} snapshot time(s) shared by every run\n", field, times.size());
    return;
  }
  const Grid g = pod_grid(s, frames, from_air, o);
  PodField p;
  p.field = field;
  p.source = from_air ? "air snapshots (air_*.h5)"
                      : fmt::format("particle snapshots deposited on cells of {:g} m (cloud-in-cell)", g.dx);
  p.cells = static_cast<int>(g.cells());
  p.snapshots = static_cast<int>(times.size());
  std::vector<Pod> pods;
  for (size_t k = 0; k < s.runs.size(); ++k) {
    const auto& r = s.runs[k];
    pods.push_back(pod_snapshots(field_matrix(r, frames[k], field, times, g, from_air, tol), true));
    p.runs.push_back(r.label);
  }
  int rmax = std::min(o.max_modes, modes_for_energy(pods[0], o.energy));
  for (const auto& q : pods) rmax = std::min<int>(rmax, static_cast<int>(q.energy.size()));
  p.modes = std::max(rmax, 0);
  for (size_t r = 0; r < pods.size(); ++r) {
    p.fraction.push_back(pods[r].total > 0 ? Eigen::VectorXd(pods[r].energy / pods[r].total) : pods[r].energy);
    if (p.modes == 0) {
      p.angles_deg.emplace_back();
      p.spectrum_dev.push_back(NAN);
      p.agrees.push_back(false);
      continue;
    }
    const Eigen::VectorXd th = principal_angles(pods[0].modes.leftCols(p.modes), pods[r].modes.leftCols(p.modes));
    p.angles_deg.push_back(th * (180.0 / std::numbers::pi));
    double dev = 0;
    for (int k = 0; k < p.modes; ++k) dev = std::max(dev, std::fabs(p.fraction[r](k) - p.fraction[0](k)));
    p.spectrum_dev.push_back(dev);
    p.agrees.push_back(dev <= s.thresholds["spectrum"] && p.angles_deg.back().maxCoeff() <= s.thresholds["angle"]);
  }
  s.pod.push_back(std::move(p));
}

}  // namespace

Study analyse_study(const std::vector<RunPlan>& runs, const StudyInfo& info, double t0, const Thresholds& th,
                    const PodOptions& pod) {
  Study s;
  s.t0 = t0;
  s.runs = runs;
  s.info = info;
  s.thresholds = th;
  // Budgets (energy.csv).
  for (const auto& r : runs) {
    const fs::path e = fs::path(r.dir) / "energy.csv";
    if (!fs::exists(e)) throw Error(fmt::format("{}: no energy.csv (run it without --report-only)", r.dir));
    s.budgets.push_back(read_budget(e.string(), r.label, r.ratio, t0));
  }
  s.scales = budget_scales(s.budgets[0]);
  s.budget = compare_budgets(s.budgets, 0, s.scales);
  // Groups: "budgets" (the energetically significant terms, momentum, closure) and
  // "rotation" (the parcels' own rotational energy, 1e-2 of S_E and judged on its own peak).
  // e_rot_orig has a verdict of its own but no group: it differs by l^2 by construction (eq. 5).
  for (size_t r = 0; r < runs.size(); ++r) {
    GroupVerdict v{runs[r].label, "budgets", 0, 0}, rot{runs[r].label, "rotation", 0, 0};
    for (const auto& q : budget_quantities()) {
      if (r == 0 && q != "closure") continue;
      const bool ok = s.budget[r].max_dev[q] <= th[budget_threshold(q)];
      s.budget_agrees[runs[r].label][q] = ok;
      if (q == "e_rot_orig") continue;
      GroupVerdict& g = q == "e_rot" ? rot : v;
      g.total++, g.passed += ok;
    }
    s.verdicts.push_back(v);
    if (rot.total) s.verdicts.push_back(rot);
  }
  // Observables.
  double dmax = 0;
  for (const auto& r : runs) dmax = std::max(dmax, r.size * info.d_original);
  s.profile = {info.lo.x, info.hi.x, info.lo.y, info.hi.y, info.lo.z, 2 * dmax};
  for (const auto& r : runs) s.observables.push_back(read_observables(r.dir, s.profile, t0));
  compare_scalars(s);
  for (size_t r = 1; r < runs.size(); ++r) {
    compare_curve(s, "transfer_rate", s.observables[0].transfer_rate, r, s.observables[r].transfer_rate);
    for (const auto& [n, c] : s.observables[0].pressure)
      if (s.observables[r].pressure.count(n)) compare_curve(s, n, c, r, s.observables[r].pressure.at(n));
  }
  compare_profiles(s);
  for (size_t r = 1; r < runs.size(); ++r) {
    GroupVerdict v{runs[r].label, "observables", 0, 0};
    for (const auto& row : s.observable_rows)
      if (row.run == runs[r].label) v.total++, v.passed += row.agrees;
    s.verdicts.push_back(v);
  }
  // Reduced-order comparison.
  pod_field(s, "solid_fraction", pod);
  if (info.air) pod_field(s, "pressure", pod);
  for (const auto& p : s.pod)
    for (size_t r = 1; r < p.runs.size(); ++r) s.verdicts.push_back({p.runs[r], "pod_" + p.field, p.agrees[r] ? 1 : 0, 1});
  return s;
}

}  // namespace cgdem::scaling
