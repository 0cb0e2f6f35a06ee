#include "scaling/spectrum_series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"

namespace cgdem::scaling {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  size_t start = 0;
  for (size_t c; (c = line.find(',', start)) != std::string::npos; start = c + 1) f.push_back(line.substr(start, c - start));
  f.push_back(line.substr(start));
  return f;
}

double number(const std::string& text, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw Error(fmt::format("{}: '{}' is not a number", where, text));
  if (!std::isfinite(v)) throw Error(fmt::format("{}: non-finite value '{}'", where, text));
  return v;
}

}  // namespace

PressureSeries read_pressure_series(const std::string& run_dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(run_dir)) throw Error(fmt::format("spectrum: run folder '{}' does not exist", run_dir));
  PressureSeries s;
  s.source = (fs::path(run_dir) / "diagnostics.csv").string();
  std::ifstream in(s.source);
  if (!in)
    throw Error(fmt::format("spectrum: cannot read '{}' (a run with [walls.die_filling] writes it)", s.source));
  std::vector<size_t> p_col;
  size_t t_col = std::string::npos, n_fields = 0;
  std::string line;
  double grid_t0 = 0, grid_dt = 0;  // "# rows: at t = T0 s + k DT s" (app/run_schedule.hpp)
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("# rows: at t = ", 0) == 0 && std::sscanf(line.c_str(), "# rows: at t = %lf s + k %lf s", &grid_t0, &grid_dt) != 2)
      grid_dt = 0;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> f = split(line);
    if (n_fields == 0) {  // the column line
      n_fields = f.size();
      // t_s and p_<cell>_Pa (io/csv_series.hpp), or t and p_<cell> (files written before).
      for (size_t c = 0; c < f.size(); ++c)
        if (f[c] == "t_s" || (f[c] == "t" && t_col == std::string::npos)) t_col = c;
      const bool units = f[t_col == std::string::npos ? 0 : t_col] == "t_s";
      for (size_t c = 0; c < f.size(); ++c) {
        std::string cell = f[c].rfind("p_", 0) == 0 ? f[c].substr(2) : "";
        if (units) cell = cell.size() > 3 && cell.compare(cell.size() - 3, 3, "_Pa") == 0 ? cell.substr(0, cell.size() - 3) : "";
        if (!cell.empty()) {
          p_col.push_back(c);
          s.cells.push_back(cell);
        }
      }
      if (t_col == std::string::npos) throw Error(fmt::format("{}: no column 't_s' (or 't') in '{}'", s.source, line));
      if (p_col.empty()) throw Error(fmt::format("{}: no pressure column (p_<cell>) in '{}'", s.source, line));
      s.p.resize(p_col.size());
      continue;
    }
    if (f.size() != n_fields)
      throw Error(fmt::format("{}:{}: {} values, the column line has {}", s.source, n, f.size(), n_fields));
    const double t = number(f[t_col], fmt::format("{}:{}", s.source, n));
    // A run's last row is its final state, off the row grid when time.end is: left out.
    if (grid_dt > 0 && std::abs((t - grid_t0) / grid_dt - std::round((t - grid_t0) / grid_dt)) > 1e-3) continue;
    // A restarted run continues the file from its checkpoint: rows of the interrupted run
    // at or after the restart time are superseded by the new ones.
    while (!s.t.empty() && s.t.back() >= t) {
      s.t.pop_back();
      for (auto& p : s.p) p.pop_back();
    }
    s.t.push_back(t);
    for (size_t c = 0; c < p_col.size(); ++c) s.p[c].push_back(number(f[p_col[c]], fmt::format("{}:{}", s.source, n)));
  }
  if (n_fields == 0) throw Error(fmt::format("{}: no column line", s.source));
  if (s.t.size() < 2) throw Error(fmt::format("{}: {} data rows, a spectrum needs more", s.source, s.t.size()));
  return s;
}

PressureSeries select(const PressureSeries& s, const std::vector<std::string>& cells, std::optional<double> from,
                      std::optional<double> to) {
  PressureSeries r;
  r.source = s.source;
  std::vector<size_t> idx;
  if (cells.empty())
    for (size_t c = 0; c < s.cells.size(); ++c) idx.push_back(c);
  for (const std::string& name : cells) {
    const auto it = std::find(s.cells.begin(), s.cells.end(), name);
    if (it == s.cells.end()) {
      std::string have;
      for (const auto& c : s.cells) have += (have.empty() ? "" : ",") + c;
      throw Error(fmt::format("--cells: {} has no cell '{}' (it has {})", s.source, name, have));
    }
    idx.push_back(it - s.cells.begin());
  }
  for (size_t c : idx) r.cells.push_back(s.cells[c]);
  r.p.resize(idx.size());
  for (size_t i = 0; i < s.t.size(); ++i) {
    if ((from && s.t[i] < *from) || (to && s.t[i] > *to)) continue;
    r.t.push_back(s.t[i]);
    for (size_t c = 0; c < idx.size(); ++c) r.p[c].push_back(s.p[idx[c]][i]);
  }
  if (r.t.size() < 2)
    throw Error(fmt::format("--from/--to: {} has {} sample(s) in [{}, {}] s (its data span [{}, {}] s)", s.source,
                            r.t.size(), from ? fmt::format("{}", *from) : "start", to ? fmt::format("{}", *to) : "end",
                            s.t.front(), s.t.back()));
  return r;
}

double uniform_interval(const PressureSeries& s, double rel_tol) {
  std::vector<double> d(s.t.size() - 1);
  for (size_t i = 0; i + 1 < s.t.size(); ++i) d[i] = s.t[i + 1] - s.t[i];
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double dt = sorted[sorted.size() / 2];
  if (!(dt > 0)) throw Error(fmt::format("{}: t does not increase (median interval {} s)", s.source, dt));
  for (size_t i = 0; i < d.size(); ++i)
    if (std::abs(d[i] - dt) > rel_tol * dt)
      throw Error(fmt::format(
          "{}: sampling is not uniform: t = {:.10g} -> {:.10g} s is an interval of {:.6g} s, the median is {:.6g} s "
          "(relative deviation {:.3g} > {}); restrict --from/--to or resample with --dt",
          s.source, s.t[i], s.t[i + 1], d[i], dt, std::abs(d[i] - dt) / dt, rel_tol));
  return dt;
}

PressureSeries resample(const PressureSeries& s, double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error(fmt::format("--dt: {} s is not a positive interval", dt));
  PressureSeries r;
  r.source = s.source;
  r.cells = s.cells;
  r.p.resize(s.p.size());
  const double t0 = s.t.front();
  const size_t n = static_cast<size_t>(std::floor((s.t.back() - t0) / dt * (1 + 1e-12))) + 1;
  size_t j = 0;  // s.t[j] <= t < s.t[j+1]
  for (size_t i = 0; i < n; ++i) {
    const double t = t0 + i * dt;
    while (j + 2 < s.t.size() && s.t[j + 1] <= t) ++j;
    const double a = std::clamp((t - s.t[j]) / (s.t[j + 1] - s.t[j]), 0.0, 1.0);
    r.t.push_back(t);
    for (size_t c = 0; c < s.p.size(); ++c) r.p[c].push_back((1 - a) * s.p[c][j] + a * s.p[c][j + 1]);
  }
  return r;
}

}  // namespace cgdem::scaling
