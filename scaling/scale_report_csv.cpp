// The CSV files of the report (one per series family); scale_report.cpp writes scale.md.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/atomic_file.hpp"
#include "scaling/scale_report.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

namespace detail {

std::string g10(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : "nan"; }

namespace {

// budget_<run>.csv and deviation_<run>.csv: per run, its budget per unit mass and its
// deviation from l = 1 on the common time base; budget_summary.csv: per run and quantity,
// the largest deviation and the verdict.
void write_budget_csvs(const Study& s, const fs::path& dir) {
  const auto& Q = budget_quantities();
  for (const auto& c : s.budget) {
    std::string a = "t", d = "t";
    for (const auto& q : Q) a += "," + q, d += "," + q;
    a += "\n", d += "\n";
    for (size_t i = 0; i < c.t.size(); ++i) {
      a += g10(c.t[i]), d += g10(c.t[i]);
      for (const auto& q : Q) a += "," + g10(c.value.at(q)[i]), d += "," + g10(c.dev.at(q)[i]);
      a += "\n", d += "\n";
    }
    io::write_file_atomic((dir / ("budget_" + c.label + ".csv")).string(), a);
    io::write_file_atomic((dir / ("deviation_" + c.label + ".csv")).string(), d);
  }
  std::string sum = "run,quantity,unit,scale_kind,scale,max_deviation,t_at_max_s,mean_ratio_to_l1,threshold,verdict\n";
  for (const auto& c : s.budget)
    for (const auto& q : Q) {
      const auto& ag = s.budget_agrees.at(c.label);
      if (!ag.count(q)) continue;
      sum += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", c.label, q, budget_unit(q), budget_scale_kind(q),
                         g10(q == "closure" ? s.scales.energy : s.scales.of(q)), g10(c.max_dev.at(q)),
                         g10(c.t_max_dev.at(q)), g10(c.mean_ratio.at(q)),
                         g10(s.thresholds[budget_threshold(q)]),
                         ag.at(q) ? "agrees" : "differs");
    }
  io::write_file_atomic((dir / "budget_summary.csv").string(), sum);
}

// observables.csv (one row per run and observable with its verdict), profile.csv (the final
// pile-height profiles) and curves.csv (the die-filling diagnostics' time curves, each run
// on its own times, long format; only when a run has them).
void write_observable_csvs(const Study& s, const fs::path& dir) {
  std::string ob = "run,observable,metric,value,reference,deviation,threshold,verdict\n";
  for (const auto& r : s.observable_rows)
    ob += fmt::format("{},{},{},{},{},{},{},{}\n", r.run, r.name, r.metric, g10(r.value), g10(r.reference),
                      g10(r.deviation), g10(r.threshold), r.agrees ? "agrees" : "differs");
  io::write_file_atomic((dir / "observables.csv").string(), ob);
  std::string pr = "x_m";
  for (const auto& r : s.runs) pr += ",h_" + r.label + "_m";
  pr += "\n";
  const auto& x = s.observables[0].profile_x;
  for (size_t i = 0; i < x.size(); ++i) {
    pr += g10(x[i]);
    for (const auto& o : s.observables) pr += "," + (i < o.profile_h.size() ? g10(o.profile_h[i]) : "nan");
    pr += "\n";
  }
  io::write_file_atomic((dir / "profile.csv").string(), pr);
  std::string cv = "run,curve,t_s,value\n";
  bool any = false;
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const auto& o = s.observables[r];
    for (size_t i = 0; i < o.transfer_rate.t.size(); ++i, any = true)
      cv += fmt::format("{},transfer_rate_kg_s,{},{}\n", s.runs[r].label, g10(o.transfer_rate.t[i]),
                        g10(o.transfer_rate.y[i]));
    for (const auto& [n, c] : o.pressure)
      for (size_t i = 0; i < c.t.size(); ++i) cv += fmt::format("{},{}_Pa,{},{}\n", s.runs[r].label, n, g10(c.t[i]), g10(c.y[i]));
  }
  if (any) io::write_file_atomic((dir / "curves.csv").string(), cv);
}

// pod_<field>_spectrum.csv and pod_<field>_angles.csv: per POD field, the modal energy
// fractions of each run and the principal angles to l = 1.
void write_pod_csvs(const Study& s, const fs::path& dir) {
  for (const auto& p : s.pod) {
    std::string sp = "mode";
    for (const auto& r : p.runs) sp += ",fraction_" + r;
    sp += "\n";
    long kmax = 0;
    for (const auto& f : p.fraction) kmax = std::max<long>(kmax, f.size());
    for (long k = 0; k < kmax; ++k) {
      sp += std::to_string(k + 1);
      for (const auto& f : p.fraction) sp += "," + (k < f.size() ? g10(f(k)) : "nan");
      sp += "\n";
    }
    io::write_file_atomic((dir / ("pod_" + p.field + "_spectrum.csv")).string(), sp);
    std::string an = "run,index,angle_deg\n";
    for (size_t r = 0; r < p.runs.size(); ++r)
      for (long i = 0; i < p.angles_deg[r].size(); ++i)
        an += fmt::format("{},{},{}\n", p.runs[r], i + 1, g10(p.angles_deg[r](i)));
    io::write_file_atomic((dir / ("pod_" + p.field + "_angles.csv")).string(), an);
  }
}

}  // namespace

void write_report_csvs(const Study& s, const std::string& dir) {
  write_budget_csvs(s, dir);
  write_observable_csvs(s, dir);
  write_pod_csvs(s, dir);
}

}  // namespace detail

}  // namespace cgdem::scaling
