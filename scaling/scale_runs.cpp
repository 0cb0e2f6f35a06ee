#include "scaling/scale_runs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <toml.hpp>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "diagnostics/die_diagnostics.hpp"
#include "app/flow_case.hpp"
#include "app/run_command.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "scaling/csv_table.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;
using TomlValue = toml::basic_value<toml::preserve_comments, std::map, std::vector>;

std::vector<RunPlan> plan_runs(const std::vector<double>& ratios, double simply_large, const std::string& report_dir) {
  if (ratios.empty()) throw Error("--ratios: give at least two ratios, e.g. --ratios 1,2,3");
  std::vector<double> l = ratios;
  std::sort(l.begin(), l.end());
  for (size_t i = 0; i < l.size(); ++i) {
    if (!(l[i] >= 1) || !std::isfinite(l[i])) throw Error(fmt::format("--ratios: {:g} is not a ratio >= 1", l[i]));
    if (i && l[i] == l[i - 1]) throw Error(fmt::format("--ratios: {:g} is given twice", l[i]));
  }
  if (l.front() != 1) throw Error("--ratios: must contain 1, the reference (original particles)");
  if (l.size() < 2 && simply_large == 0) throw Error("--ratios: give at least one ratio besides 1 (or --simply-large)");
  if (simply_large != 0 && !(simply_large > 1 && std::isfinite(simply_large)))
    throw Error(fmt::format("--simply-large: {:g} must be a size factor > 1", simply_large));
  std::vector<RunPlan> out;
  for (double x : l) {
    RunPlan r;
    r.label = fmt::format("l={:g}", x);
    r.ratio = r.size = x;
    r.dir = (fs::path(report_dir) / r.label).string();
    r.case_file = (fs::path(r.dir) / "case.toml").string();
    out.push_back(r);
  }
  if (simply_large > 0) {
    RunPlan r;
    r.label = fmt::format("simply_large_{:g}", simply_large);
    r.ratio = 1;
    r.size = simply_large;
    r.simply_large = true;
    r.dir = (fs::path(report_dir) / r.label).string();
    r.case_file = (fs::path(r.dir) / "case.toml").string();
    out.push_back(r);
  }
  return out;
}

namespace {

double number_of(const TomlValue& v, const std::string& where) {
  if (v.is_floating()) return v.as_floating();
  if (v.is_integer()) return static_cast<double>(v.as_integer());
  throw Error(fmt::format("{}: expected a number", where));
}

}  // namespace

void write_derived_case(const std::string& base_case, const RunPlan& r) {
  TomlValue doc;
  try {
    doc = toml::parse<toml::preserve_comments, std::map, std::vector>(base_case);
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: {}", base_case, e.what()));
  }
  auto& root = doc.as_table();
  if (!root.count("particles") || !root.at("particles").is_table())
    throw Error(fmt::format("{}: no [particles] section", base_case));
  auto& particles = root.at("particles").as_table();
  if (particles.count("file"))
    throw Error(fmt::format("{}: particles.file: particles read from a file cannot be re-scaled by cgdem scale; "
                            "use [[particles.insert]] with solid_volume",
                            base_case));
  if (!particles.count("species") || !particles.at("species").is_array())
    throw Error(fmt::format("{}: particles.species: at least one [[particles.species]] is required", base_case));
  // Base parcel volumes by species name (for count -> solid_volume).
  std::map<std::string, double> base_volume;
  for (auto& sv : particles.at("species").as_array()) {
    auto& s = sv.as_table();
    const std::string name = s.count("name") && s.at("name").is_string() ? s.at("name").as_string().str : "";
    if (!s.count("d_original")) throw Error(fmt::format("{}: particles.species.d_original is missing", base_case));
    const double d0 = number_of(s.at("d_original"), base_case + ": particles.species.d_original");
    const double l0 = s.count("ratio") ? number_of(s.at("ratio"), base_case + ": particles.species.ratio") : 1.0;
    base_volume[name] = std::numbers::pi * std::pow(l0 * d0, 3) / 6;
    if (r.simply_large) {
      s["d_original"] = TomlValue(d0 * r.size);
      s["ratio"] = TomlValue(1.0);
    } else {
      s["ratio"] = TomlValue(r.ratio);
    }
  }
  if (particles.count("insert") && particles.at("insert").is_array())
    for (auto& iv : particles.at("insert").as_array()) {
      auto& ins = iv.as_table();
      if (!ins.count("count")) continue;
      const std::string sp = ins.count("species") && ins.at("species").is_string() ? ins.at("species").as_string().str : "";
      if (!base_volume.count(sp))
        throw Error(fmt::format("{}: particles.insert.species: unknown species \"{}\"", base_case, sp));
      const double n = number_of(ins.at("count"), base_case + ": particles.insert.count");
      ins.erase("count");
      ins["solid_volume"] = TomlValue(n * base_volume[sp]);
    }
  if (!root.count("output")) root["output"] = TomlValue(toml::table{});
  root.at("output").as_table()["dir"] = TomlValue(fs::absolute(r.dir).string());
  fs::create_directories(r.dir);
  std::ostringstream text;
  text << fmt::format("# derived by cgdem scale from {}: {}\n", fs::absolute(base_case).string(),
                      r.simply_large ? fmt::format("simply large, d_original x {:g}, ratio 1", r.size)
                                     : fmt::format("coarse-grain ratio l = {:g}", r.ratio));
  text << toml::format(doc);
  io::write_file_atomic(r.case_file, text.str());
}

StudyInfo read_study_info(const std::string& case_file, const std::vector<std::string>& sets, const std::string& out) {
  StudyInfo s;
  // Loaded, overridden and validated by cgdem run's own resolver: the same case paths, the
  // same errors, and exactly the text its config.resolved.toml will hold (finished_run).
  s.resolved = app::resolve_case_file({case_file, sets, out, ""});
  // What the study needs is read back from that resolved text (every default filled in).
  Config cfg = Config::from_string(s.resolved, case_file);
  if (app::is_flow_case(cfg))
    throw Error(fmt::format("{}: a single-phase flow case ([flow]) has no particles to coarse-grain", case_file));
  const app::DemCase c = app::read_dem_case(cfg);
  const app::AirCase air = app::read_air_case(cfg, c.dem);
  const diagnostics::DiagnosticsSpec diag = diagnostics::read_diagnostics(cfg);
  s.lo = c.dem.domain.lo;
  s.hi = c.dem.domain.hi;
  s.periodic = {c.dem.periodic[0], c.dem.periodic[1], c.dem.periodic[2]};
  s.t_start = c.t_start;
  s.t_end = c.t_end;
  s.d_original = INFINITY;
  for (const auto& sp : c.species) {
    s.d_parcel_max = std::max(s.d_parcel_max, sp.diameter());
    s.d_original = std::min(s.d_original, sp.d_original);
  }
  s.air = air.enabled;
  s.air_dx = air.enabled ? air.grid.dx : 0.0;
  s.die_filling = diag.enabled;
  return s;
}

bool finished_run(const RunPlan& r, const StudyInfo& info, std::string* why) {
  const fs::path dir(r.dir), stored = dir / "config.resolved.toml";
  auto say = [&](const std::string& s) {
    if (why) *why = s;
    return false;
  };
  if (!fs::exists(stored)) return say("no run in " + r.dir);
  std::ifstream in(stored);
  std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The first line is the "# cgdem <revision> resolved configuration of <case>" comment.
  const size_t nl = rest.find('\n');
  rest = nl == std::string::npos ? "" : rest.substr(nl + 1);
  if (rest != info.resolved) return say(fmt::format("{} holds a run of a different configuration", r.dir));
  if (fs::exists(dir / "metrics.csv")) return true;
  if (!fs::exists(dir / "energy.csv")) return say("no energy.csv in " + r.dir);
  try {
    const CsvTable e = read_csv_table((dir / "energy.csv").string());
    const double span = info.t_end - info.t_start;
    if (e.rows() && e.col("t_s").back() >= info.t_end - 1e-6 * span) return true;
  } catch (const Error&) {
  }
  return say(fmt::format("the run in {} did not finish", r.dir));
}

bool run_or_pick_up(const RunPlan& r, const std::vector<std::string>& sets, const StudyInfo& info) {
  std::string why;
  if (finished_run(r, info, &why)) {
    fmt::print("cgdem scale: {}: picking up the finished run in {}\n", r.label, r.dir);
    return false;
  }
  fmt::print("cgdem scale: {}: running ({})\n", r.label, why);
  std::fflush(stdout);
  const int rc = app::run_case_file({r.case_file, sets, fs::absolute(r.dir).string(), ""});
  if (rc != 0) throw Error(fmt::format("cgdem scale: the run {} ended with status {}", r.label, rc));
  return true;
}

}  // namespace cgdem::scaling
