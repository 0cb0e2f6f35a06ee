#include "scaling/converge_command.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include "app/run_command.hpp"
#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "io/atomic_file.hpp"
#include "io/metrics.hpp"
#include "scaling/richardson.hpp"

namespace cgdem::scaling {

namespace {

namespace fs = std::filesystem;

double parse_number(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) throw Error(fmt::format("{}: '{}' is not a number", what, text));
  return v;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

struct Vary {
  std::string key;
  std::vector<std::string> texts;  // as given (run folder names and TOML values)
  std::vector<double> values;
};

Vary parse_vary(const std::string& arg) {
  const auto eq = arg.find('=');
  Vary v;
  v.key = trim(arg.substr(0, eq));
  if (eq == std::string::npos || v.key.empty())
    throw Error(fmt::format("--vary '{}': expected key.path=v1,v2,v3", arg));
  std::stringstream in(arg.substr(eq + 1));
  for (std::string t; std::getline(in, t, ',');) {
    t = trim(t);
    const double x = parse_number(t, "--vary " + v.key + ": level");
    if (std::find(v.values.begin(), v.values.end(), x) != v.values.end())
      throw Error(fmt::format("--vary {}: level {} is given twice", v.key, t));
    v.texts.push_back(t);
    v.values.push_back(x);
  }
  if (v.values.size() < 3)
    throw Error(fmt::format("--vary {}: an observed order needs at least 3 levels, got {}", v.key, v.values.size()));
  return v;
}

std::map<std::string, double> parse_exact(const std::vector<std::string>& args, const std::vector<std::string>& metrics) {
  std::map<std::string, double> out;
  for (const auto& a : args) {
    const auto eq = a.find('=');
    const std::string name = trim(a.substr(0, eq));
    if (eq == std::string::npos || name.empty()) throw Error(fmt::format("--exact '{}': expected NAME=VALUE", a));
    if (std::find(metrics.begin(), metrics.end(), name) == metrics.end())
      throw Error(fmt::format("--exact {}: not one of the --metric names", name));
    out[name] = parse_number(trim(a.substr(eq + 1)), "--exact " + name);
  }
  return out;
}

// config.resolved.toml without its first line (the revision and case path comment).
std::string resolved_body(const std::string& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  const auto nl = s.find('\n');
  return (s.rfind("#", 0) == 0 && nl != std::string::npos) ? s.substr(nl + 1) : s;
}

std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string l;
  std::getline(in, l);
  return l;
}

struct LevelRun {
  std::string label;  // key=value, also the folder name
  double value = 0, h = 0;
  io::Metrics metrics;
};

// Runs (or reuses) one level and returns its metrics.
LevelRun run_level(const app::RunRequest& req, const std::string& label, bool reuse) {
  const std::string metrics_csv = (fs::path(req.output) / "metrics.csv").string();
  const std::string resolved = (fs::path(req.output) / "config.resolved.toml").string();
  if (reuse && fs::exists(metrics_csv) && resolved_body(resolved) == app::resolve_case_file(req)) {
    const std::string header = first_line(resolved);
    fmt::print("converge: {}: reusing {} ({})\n", label, req.output, header.substr(std::min<size_t>(2, header.size())));
    if (header.find(kGitRevision) == std::string::npos)
      fmt::print("converge: note: {} was written by another revision than this binary ({})\n", label, kGitRevision);
  } else {
    fmt::print("converge: {}: running into {}\n", label, req.output);
    std::fflush(stdout);
    Stopwatch clock;
    int rc = 0;
    try {
      rc = app::run_case_file(req);
    } catch (const Error& e) {
      throw Error(fmt::format("level {}: {}", label, e.what()));
    }
    if (rc != 0) throw Error(fmt::format("level {}: the run exited with status {}", label, rc));
    fmt::print("converge: {}: done in {:.1f} s\n", label, clock.seconds());
  }
  if (!fs::exists(metrics_csv))
    throw Error(fmt::format("level {}: the run wrote no metrics.csv in {} (does this kind of case write metrics?)",
                            label, req.output));
  return {label, 0, 0, io::read_metrics(metrics_csv)};
}

// One metric across the levels, sorted fine to coarse (h ascending).
struct MetricStudy {
  std::string name;
  std::vector<std::string> labels;
  std::vector<Level> levels;
  std::vector<TripleResult> triples;  // triples[j] has levels[j] as its finest level
  bool has_exact = false;
  double exact = 0;
  PowerFit fit;
  std::vector<std::string> not_computed;  // levels whose run did not write the metric (io::may_be_left_out)
};

std::string num(double x, const char* f = "{:.6g}") { return std::isfinite(x) ? fmt::format(fmt::runtime(f), x) : "nan"; }

// Row i (coarse to fine) of the table: the level, its difference to the next coarser one,
// and the triple whose finest level it is.
struct Row {
  std::string label, h, f, diff, r, p, behaviour, f_ext, gci, gci_rel;
};
std::vector<Row> rows(const MetricStudy& m) {
  std::vector<Row> out;
  const size_t n = m.levels.size();
  for (size_t k = n; k-- > 0;) {  // k: index fine-first; printed coarse to fine
    Row r;
    r.label = m.labels[k], r.h = num(m.levels[k].h), r.f = num(m.levels[k].f, "{:.10g}");
    if (std::count(m.not_computed.begin(), m.not_computed.end(), r.label)) r.f = "not computed";
    if (k + 1 < n) {
      if (std::isfinite(m.levels[k].f) && std::isfinite(m.levels[k + 1].f))
        r.diff = num(m.levels[k].f - m.levels[k + 1].f, "{:.4e}");
      r.r = num(m.levels[k + 1].h / m.levels[k].h, "{:.4f}");
    }
    if (k < m.triples.size()) {
      const TripleResult& t = m.triples[k];
      r.behaviour = to_string(t.behaviour);
      if (t.behaviour == Behaviour::Monotone) {
        r.p = num(t.order, "{:.4f}");
        r.f_ext = num(t.extrapolated, "{:.10g}");
        r.gci = num(t.gci_fine, "{:.4e}");
        r.gci_rel = std::isfinite(t.gci_fine_rel) ? num(t.gci_fine_rel, "{:.4e}") : "";
      }
    }
    out.push_back(r);
  }
  return out;
}

// The one-line verdict of a metric (finest triple), the line the CLI tests read.
std::string summary(const MetricStudy& m) {
  if (!m.not_computed.empty())
    return fmt::format("converge: {}: not computed at {} (the run wrote no such metric: cgdem run leaves out what it "
                       "cannot compute, e.g. the pressures of a run without air); no order",
                       m.name, fmt::join(m.not_computed, ", "));
  if (m.triples.empty()) return fmt::format("converge: {}: fewer than 3 levels", m.name);
  const TripleResult& t = m.triples.front();
  const std::string which = fmt::format("finest triple {}, {}, {}", m.labels[2], m.labels[1], m.labels[0]);
  if (t.behaviour != Behaviour::Monotone)
    return fmt::format("converge: {}: observed order undefined: {} ({}; spread {:.4e})", m.name, to_string(t.behaviour),
                       which, t.spread);
  std::string s = fmt::format("converge: {}: observed order p = {:.4f} (monotone, {}), extrapolated {:.10g}, GCI {:.4e}",
                              m.name, t.order, which, t.extrapolated, t.gci_fine);
  if (std::isfinite(t.gci_fine_rel)) s += fmt::format(" ({:.3g} % of the finest value)", 100 * t.gci_fine_rel);
  return s;
}

std::string fit_line(const MetricStudy& m) {
  if (!m.has_exact) return "";
  if (!std::isfinite(m.fit.order))
    return fmt::format("converge: {}: least-squares order undefined (fewer than 2 levels differ from {:g})", m.name, m.exact);
  return fmt::format("converge: {}: least-squares order p = {:.4f} over {} levels (|f - {:g}| = C h^p, C = {:.4e}, "
                     "max log residual {:.3f}, sign changes {})",
                     m.name, m.fit.order, m.fit.levels, m.exact, m.fit.constant, m.fit.max_log_residual,
                     m.fit.sign_changes);
}

std::string csv_text(const std::vector<MetricStudy>& studies) {
  std::string s = "metric,level,h,value,difference,ratio,order,behaviour,extrapolated,gci,gci_rel,"
                  "fit_order,fit_constant\n";
  for (const auto& m : studies) {
    const std::string fo = m.has_exact ? num(m.fit.order) : "", fc = m.has_exact ? num(m.fit.constant) : "";
    for (const Row& r : rows(m))
      s += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", m.name, r.label, r.h, r.f, r.diff, r.r, r.p,
                       r.behaviour, r.f_ext, r.gci, r.gci_rel, fo, fc);
  }
  return s;
}

std::string markdown_text(const std::vector<MetricStudy>& studies, const std::string& header) {
  std::string s = header;
  for (const auto& m : studies) {
    s += fmt::format("\n## {}\n\n| level | h | value | diff. to coarser | r | p | behaviour | extrapolated | GCI | "
                     "GCI rel. |\n|---|---|---|---|---|---|---|---|---|---|\n",
                     m.name);
    for (const Row& r : rows(m))
      s += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.label, r.h, r.f, r.diff, r.r,
                       r.p, r.behaviour, r.f_ext, r.gci, r.gci_rel);
    s += "\n" + summary(m).substr(10) + "\n";
    if (m.has_exact) s += "\n" + fit_line(m).substr(10) + "\n";
  }
  return s;
}

// The levels, in the order given: each run (or reused) into out/<key>=<value>/ with the
// common --set keys and its level applied last, its h taken as --h-from says (positive, no
// two levels alike), every requested metric present or one cgdem may leave out.
std::vector<LevelRun> run_levels(const std::string& case_file, const std::vector<std::string>& common_sets,
                                 const Vary& vary, const std::string& h_from, const std::vector<std::string>& metrics,
                                 const std::string& out, bool reuse) {
  std::vector<LevelRun> runs;
  for (size_t i = 0; i < vary.values.size(); ++i) {
    const std::string label = vary.key + "=" + vary.texts[i];
    std::vector<std::string> sets = common_sets;
    sets.push_back(label);
    LevelRun run = run_level({case_file, sets, (fs::path(out) / label).string(), ""}, label, reuse);
    run.value = vary.values[i];
    if (h_from == "value") run.h = run.value;
    else if (h_from == "1/value") run.h = 1.0 / run.value;
    else run.h = io::metric(run.metrics, h_from, label + " (--h-from)");
    if (!(run.h > 0) || !std::isfinite(run.h))
      throw Error(fmt::format("--h-from {}: h = {:g} at {} is not a positive number", h_from, run.h, label));
    for (const auto& r : runs)
      if (r.h == run.h) throw Error(fmt::format("--h-from {}: {} and {} have the same h = {:g}", h_from, r.label, label, run.h));
    for (const auto& name : metrics)  // a misspelt name stops here; one cgdem may leave out is "not computed"
      if (!io::may_be_left_out(name) || io::has_metric(run.metrics, name))
        io::metric(run.metrics, name, (fs::path(out) / label / "metrics.csv").string());
    runs.push_back(std::move(run));
  }
  return runs;
}

// One study per metric over the levels sorted by h (finest first): the triples' orders and
// extrapolations, and the power-law fit where --exact gives the limit; a metric missing at
// some level is analysed no further.
std::vector<MetricStudy> study_metrics(const std::vector<std::string>& metrics, const std::vector<LevelRun>& runs,
                                       const std::map<std::string, double>& exact) {
  std::vector<size_t> order(runs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return runs[a].h < runs[b].h; });
  std::vector<MetricStudy> studies;
  for (const auto& name : metrics) {
    MetricStudy m;
    m.name = name;
    for (size_t i : order) {
      m.labels.push_back(runs[i].label);
      const bool computed = io::has_metric(runs[i].metrics, name);
      if (!computed) m.not_computed.push_back(runs[i].label);
      m.levels.push_back({runs[i].h, computed ? io::metric(runs[i].metrics, name, runs[i].label) : NAN});
    }
    if (!m.not_computed.empty()) {  // nothing to analyse: the table shows which levels lack it
      studies.push_back(std::move(m));
      continue;
    }
    try {
      m.triples = analyse_sequence(m.levels);
      if (exact.count(name)) m.has_exact = true, m.exact = exact.at(name), m.fit = fit_error_power_law(m.levels, m.exact);
    } catch (const Error& e) {
      throw Error(fmt::format("--metric {}: {}", name, e.what()));
    }
    studies.push_back(std::move(m));
  }
  return studies;
}

// The tables and the one-line verdicts on standard output.
void print_studies(const std::vector<MetricStudy>& studies, const std::string& out) {
  for (const auto& m : studies) {
    fmt::print("\n{:<28} {:>12} {:>18} {:>12} {:>8} {:>8} {:>12} {:>18} {:>11}\n", m.name, "h", "value", "diff", "r", "p",
               "behaviour", "extrapolated", "GCI");
    for (const Row& r : rows(m))
      fmt::print("{:<28} {:>12} {:>18} {:>12} {:>8} {:>8} {:>12} {:>18} {:>11}\n", r.label, r.h, r.f, r.diff, r.r, r.p,
                 r.behaviour, r.f_ext, r.gci);
  }
  fmt::print("\n");
  for (const auto& m : studies) {
    fmt::print("{}\n", summary(m));
    if (m.has_exact) fmt::print("{}\n", fit_line(m));
  }
  fmt::print("converge: tables in {}/converge.md and converge.csv\n", out);
}

}  // namespace

ConvergeCommand::ConvergeCommand(CLI::App& app)
    : sub_(app.add_subcommand("converge", "refinement study: observed order, Richardson extrapolation, GCI")),
      o_(std::make_unique<Options>()) {
  sub_->add_option("case", o_->case_file, "case file (TOML)")->required()->check(CLI::ExistingFile);
  sub_->add_option("--vary", o_->vary, "key.path=v1,v2,v3[,...]: the levels (at least 3)")->required();
  sub_->add_option("--metric", o_->metrics, "metric of metrics.csv to analyse (repeatable)")->required();
  sub_->add_option("--set", o_->sets, "override a key in every run: key.path=value (repeatable)");
  sub_->add_option("--output", o_->output, "study folder (default out/converge_<case name>)");
  sub_->add_option("--h-from", o_->h_from, "h of a level: value (default), 1/value, or a metric name");
  sub_->add_option("--exact", o_->exact, "NAME=VALUE: known limit of a metric, adds a log-log fit (repeatable)");
  sub_->add_flag("--reuse", o_->reuse, "do not rerun levels whose folder has metrics.csv and the same resolved config");
  sub_->add_option("--threads", o_->threads, "OpenMP threads")->check(CLI::PositiveNumber);
}

// The options checked, the levels run, the metrics studied, the report written and printed.
int ConvergeCommand::run() const {
  const Options& o = *o_;
  const Vary vary = parse_vary(o.vary);
  const auto exact = parse_exact(o.exact, o.metrics);
  for (const auto& t : vary.texts)
    if (t.find('/') != std::string::npos) throw Error(fmt::format("--vary {}: level '{}' contains '/'", vary.key, t));
  if (o.threads > 0) omp_set_num_threads(o.threads);
  const std::string out = o.output.empty() ? "out/converge_" + fs::path(o.case_file).stem().string() : o.output;
  fs::create_directories(out);

  const std::vector<LevelRun> runs = run_levels(o.case_file, o.sets, vary, o.h_from, o.metrics, out, o.reuse);
  const std::vector<MetricStudy> studies = study_metrics(o.metrics, runs, exact);

  const std::string header = fmt::format(
      "# Convergence study of {}\n\ncgdem {}; `--vary {}`; h from `{}`{}; levels in {}/<key>=<value>/. Per consecutive "
      "triple of levels (fine h1 < h2 < h3): observed order p from e32/e21 = r21^p (r32^p - 1)/(r21^p - 1), "
      "Richardson extrapolation f1 + (f1 - f2)/(r21^p - 1), GCI = {} |f1 - f2|/(r21^p - 1) (safety factor Fs = {}); "
      "see scaling/richardson.hpp and docs/convergence.md. Rows run from coarse to fine; a row's p, extrapolated value "
      "and GCI are those of the triple whose finest level it is.\n",
      o.case_file, kGitRevision, o.vary, o.h_from, o.sets.empty() ? "" : fmt::format("; `--set {}`", fmt::join(o.sets, " ")),
      out, kGciSafetyFactor, kGciSafetyFactor);
  io::write_file_atomic((fs::path(out) / "converge.csv").string(), csv_text(studies));
  io::write_file_atomic((fs::path(out) / "converge.md").string(), markdown_text(studies, header));

  print_studies(studies, out);
  return 0;
}

}  // namespace cgdem::scaling
