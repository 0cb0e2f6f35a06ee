#include "scaling/budgets.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "scaling/csv_table.hpp"

namespace cgdem::scaling {

const std::vector<std::string>& budget_quantities() {
  static const std::vector<std::string> q{"e_trans", "e_rot",  "e_rot_orig", "e_pot", "e_damp", "e_fric",
                                          "w_walls", "w_air",  "v_x",        "v_y",   "v_z",    "closure"};
  return q;
}

std::string budget_unit(const std::string& q) { return q.rfind("v_", 0) == 0 ? "m/s" : "J/kg"; }

std::string budget_scale_kind(const std::string& q) {
  if (q.rfind("v_", 0) == 0) return "velocity";
  if (q == "e_rot" || q == "e_rot_orig") return "own peak";
  return "energy";
}

std::string budget_threshold(const std::string& q) {
  if (q == "closure") return "closure";
  const std::string k = budget_scale_kind(q);
  return k == "velocity" ? "momentum" : k == "own peak" ? "rotation" : "energy";
}

namespace {

// Drops the rows of c before t0 (output times carry rounding: 1e-9 of the span); at least
// one row must remain.
void drop_rows_before(CsvTable& c, double t0, const std::string& path) {
  const auto& t = c.col("t");
  const double tol = 1e-9 * std::max(1e-300, std::fabs(t.back() - t.front()));
  size_t first = 0;
  while (first < t.size() && t[first] < t0 - tol) ++first;
  if (first == t.size()) throw Error(fmt::format("{}: no row at or after t = {:g} s", path, t0));
  for (auto& col : c.columns) col.erase(col.begin(), col.begin() + static_cast<long>(first));
}

// Rows repeated at the same time (a restart) keep the last one: of b.t and every b.q.
void keep_last_of_repeated_times(Budget& b) {
  std::vector<size_t> keep;
  for (size_t i = 0; i < b.t.size(); ++i) {
    while (!keep.empty() && b.t[keep.back()] >= b.t[i]) keep.pop_back();
    keep.push_back(i);
  }
  if (keep.size() != b.t.size()) {
    auto pick = [&](std::vector<double>& v) {
      std::vector<double> o;
      for (size_t i : keep) o.push_back(v[i]);
      v = std::move(o);
    };
    pick(b.t);
    for (auto& [n, v] : b.q) pick(v);
  }
}

}  // namespace

Budget read_budget(const std::string& path, const std::string& label, double ratio, double t0) {
  CsvTable c = read_csv_table(path);
  if (c.rows() == 0) throw Error(fmt::format("{}: no rows", path));
  drop_rows_before(c, t0, path);
  Budget b;
  b.label = label;
  b.ratio = ratio;
  b.t = c.col("t");
  b.mass = c.col("mass").front();
  if (!(b.mass > 0)) throw Error(fmt::format("{}: solid mass {:g} kg at the first row (expected > 0)", path, b.mass));
  const double M = b.mass;
  if (c.has("particles")) b.particles = std::lround(c.col("particles").front());
  auto per_mass = [&](const std::string& name, bool from_start) {
    const auto& x = c.col(name);
    std::vector<double> y(x.size());
    for (size_t i = 0; i < x.size(); ++i) y[i] = (x[i] - (from_start ? x[0] : 0.0)) / M;
    return y;
  };
  b.q["e_trans"] = per_mass("E_kin_trans", false);
  b.q["e_rot"] = per_mass("E_kin_rot", false);
  if (c.has("E_kin_rot_orig")) {
    b.q["e_rot_orig"] = per_mass("E_kin_rot_orig", false);
  } else {  // written before the column existed: single-ratio runs only (eq. 5)
    b.rot_orig_derived = true;
    b.q["e_rot_orig"] = b.q["e_rot"];
    for (double& v : b.q["e_rot_orig"]) v /= ratio * ratio;
  }
  b.q["e_pot"] = per_mass("E_pot", true);
  // A run without the energy accounts (output.energy_accounts = false) wrote nan there: its
  // budget cannot be compared, and nan would pass through every deviation silently.
  for (const char* name : {"E_diss_damping", "E_diss_friction", "W_walls", "E_balance"})
    for (double v : c.col(name))
      if (std::isnan(v))
        throw Error(fmt::format("{}: column {} holds nan: the run was made with output.energy_accounts = false, "
                                "which does not compute the dissipation, the wall work or the balance; run it with "
                                "the accounts to compare its energy budget",
                                path, name));
  b.q["e_damp"] = per_mass("E_diss_damping", true);
  b.q["e_fric"] = per_mass("E_diss_friction", true);
  b.q["w_walls"] = per_mass("W_walls", true);
  if (c.has("W_air"))
    b.q["w_air"] = per_mass("W_air", true);
  else  // a vacuum run: no air did work (an if, not ?:, which GCC 12 misreads as a free of a non-heap object)
    b.q["w_air"].assign(b.t.size(), 0.0);
  b.q["v_x"] = per_mass("px", false);
  b.q["v_y"] = per_mass("py", false);
  b.q["v_z"] = per_mass("pz", false);
  b.q["closure"] = per_mass("E_balance", true);
  keep_last_of_repeated_times(b);
  return b;
}

double BudgetScales::of(const std::string& q) const {
  const std::string k = budget_scale_kind(q);
  if (k == "velocity") return velocity;
  if (k == "own peak") return own_peak.at(q);
  return energy;
}

BudgetScales budget_scales(const Budget& ref) {
  BudgetScales s;
  for (size_t i = 0; i < ref.t.size(); ++i) {
    const double kin = ref.q.at("e_trans")[i] + ref.q.at("e_rot")[i];
    s.energy = std::max({s.energy, std::fabs(ref.q.at("e_pot")[i]), kin, std::fabs(ref.q.at("w_walls")[i]),
                         std::fabs(ref.q.at("w_air")[i])});
  }
  s.velocity = std::sqrt(2 * s.energy);
  for (const auto& [n, v] : ref.q) {
    double m = 0;
    for (double x : v) m = std::max(m, std::fabs(x));
    s.own_peak[n] = m;
  }
  return s;
}

std::vector<BudgetComparison> compare_budgets(const std::vector<Budget>& runs, size_t ref, const BudgetScales& s) {
  std::vector<Series> spans;
  for (const auto& r : runs) spans.push_back({r.t, r.t});
  const std::vector<double> t = common_times(runs.at(ref).t, spans);
  if (t.size() < 2) throw Error("the runs share fewer than two output times of energy.csv: nothing to compare");
  std::map<std::string, std::vector<double>> ref_on_t;
  for (const auto& q : budget_quantities()) ref_on_t[q] = resample({runs[ref].t, runs[ref].q.at(q)}, t);
  std::vector<BudgetComparison> out;
  for (const auto& r : runs) {
    BudgetComparison c;
    c.label = r.label;
    c.t = t;
    for (const auto& q : budget_quantities()) {
      auto v = resample({r.t, r.q.at(q)}, t);
      const auto& b = ref_on_t[q];
      const double S = s.of(q);
      std::vector<double> d(t.size());
      for (size_t i = 0; i < t.size(); ++i) d[i] = S > 0 ? (v[i] - b[i]) / S : 0.0;
      const auto m = max_abs_deviation(v, b);
      c.max_dev[q] = S > 0 ? m.value / S : 0.0;
      c.t_max_dev[q] = t[m.index];
      double peak_ref = 0;
      for (double x : b) peak_ref = std::max(peak_ref, std::fabs(x));
      double sum = 0;
      int n = 0;
      for (size_t i = 0; i < t.size(); ++i)
        if (std::fabs(b[i]) > 0.05 * peak_ref && peak_ref > 0) sum += v[i] / b[i], ++n;
      c.mean_ratio[q] = n ? sum / n : std::nan("");
      c.value[q] = std::move(v);
      c.dev[q] = std::move(d);
    }
    // The closure is judged against zero, not against the reference's closure.
    const auto& cl = c.value["closure"];
    double worst = 0, tw = t.front();
    for (size_t i = 0; i < t.size(); ++i)
      if (std::fabs(cl[i]) > worst) worst = std::fabs(cl[i]), tw = t[i];
    c.max_dev["closure"] = s.energy > 0 ? worst / s.energy : 0.0;
    c.t_max_dev["closure"] = tw;
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace cgdem::scaling
