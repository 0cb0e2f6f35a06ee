// analyse_runs: the runs' pressure series through one Welch estimator (spectrum_report.hpp).
#include "scaling/spectrum_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.hpp"
#include "scaling/spectrum_series.hpp"

namespace cgdem::scaling {
namespace {

std::string folder_name(const std::string& dir) {
  std::filesystem::path p = std::filesystem::path(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

std::vector<std::string> run_labels(const std::vector<std::string>& dirs, const std::vector<std::string>& given) {
  if (!given.empty() && given.size() != dirs.size())
    throw Error(fmt::format("--labels: {} label(s) for {} run folder(s)", given.size(), dirs.size()));
  std::vector<std::string> labels = given;
  if (labels.empty())
    for (const auto& d : dirs) labels.push_back(folder_name(d));
  const bool same_names = std::any_of(labels.begin(), labels.end(), [&](const std::string& l) {
    return std::count(labels.begin(), labels.end(), l) > 1;
  });
  if (same_names && given.empty()) labels = dirs;  // folders of the same name: their paths
  for (const auto& l : labels) {
    if (l.empty() || l.find_first_of(",\r\n") != std::string::npos)
      throw Error(fmt::format("--labels: '{}' is not a usable label (empty, or a comma or newline in it)", l));
    if (std::count(labels.begin(), labels.end(), l) > 1) throw Error(fmt::format("--labels: '{}' given twice", l));
  }
  return labels;
}

}  // namespace

int segment_samples(const std::string& spec, double dt, size_t n, double overlap) {
  if (spec.empty()) {  // automatic: K >= 8, i.e. n - L >= 7 L (1 - overlap)
    const double longest = n / (1.0 + 7.0 * (1.0 - overlap));
    if (longest < 8)
      throw Error(fmt::format("spectrum: {} samples are too few for 8 segments of at least 8 samples (give --segment, "
                              "or widen --from/--to)",
                              n));
    return 1 << static_cast<int>(std::floor(std::log2(longest)));
  }
  int L = 0;
  char* end = nullptr;
  if (spec.back() == 's') {
    const std::string num = spec.substr(0, spec.size() - 1);
    const double seconds = std::strtod(num.c_str(), &end);
    if (num.empty() || *end != '\0' || !(seconds > 0))
      throw Error(fmt::format("--segment: '{}' is not a positive duration in seconds (e.g. 0.256s)", spec));
    L = static_cast<int>(std::lround(seconds / dt));
  } else {
    const long v = std::strtol(spec.c_str(), &end, 10);
    if (*end != '\0' || v <= 0)
      throw Error(fmt::format(
          "--segment: '{}' is neither a number of samples (e.g. 256) nor a duration in seconds (e.g. 0.256s)", spec));
    L = static_cast<int>(std::min<long>(v, 1L << 30));
  }
  if (L < 2) throw Error(fmt::format("--segment: '{}' is {} sample(s) at dt = {} s; at least 2 needed", spec, L, dt));
  if (static_cast<size_t>(L) > n)
    throw Error(fmt::format("--segment: {} samples ({} s) is longer than the {} samples of the shortest run (shorten "
                            "--segment or widen --from/--to)",
                            L, L * dt, n));
  return L;
}

SpectrumAnalysis analyse_runs(const std::vector<std::string>& run_dirs, const std::vector<std::string>& given_labels,
                              const SpectrumSettings& s) {
  if (run_dirs.empty()) throw Error("spectrum: no run folder given");
  if (!(s.overlap >= 0 && s.overlap < 1)) throw Error(fmt::format("--overlap: {} is not in [0, 1)", s.overlap));
  if (s.peaks < 1) throw Error(fmt::format("--peaks: {} (at least 1)", s.peaks));
  const std::vector<std::string> labels = run_labels(run_dirs, given_labels);

  // Series: selected range and cells, on a uniform grid (checked, or resampled onto --dt).
  std::vector<PressureSeries> series;
  std::vector<double> dt_data;
  std::vector<std::string> cells = s.cells;
  for (const std::string& dir : run_dirs) {
    PressureSeries raw = select(read_pressure_series(dir), cells, s.from, s.to);
    if (cells.empty()) cells = raw.cells;  // the first run's cells for every run
    dt_data.push_back(uniform_interval(raw, s.dt > 0 ? INFINITY : 1e-3));
    series.push_back(s.dt > 0 ? resample(raw, s.dt) : std::move(raw));
  }
  const double dt = s.dt > 0 ? s.dt : dt_data[0];
  for (size_t r = 1; r < series.size() && !(s.dt > 0); ++r)
    if (std::abs(dt_data[r] - dt) > 1e-3 * dt)
      throw Error(fmt::format("spectrum: the runs are sampled at different intervals ({}: {} s, {}: {} s); resample "
                              "them onto one with --dt",
                              labels[0], dt, labels[r], dt_data[r]));

  size_t n_min = series[0].t.size();
  for (const auto& ser : series) n_min = std::min(n_min, ser.t.size());
  SpectrumAnalysis a;
  a.settings = s;
  a.params.fs = 1.0 / dt;
  a.params.segment = segment_samples(s.segment, dt, n_min, s.overlap);
  a.params.overlap = std::min(a.params.segment - 1, static_cast<int>(std::lround(s.overlap * a.params.segment)));
  a.params.window = s.window;
  a.params.detrend = s.detrend;
  const Welch welch(a.params);
  a.factors = welch.factors();
  a.f = welch.frequencies();

  for (size_t r = 0; r < series.size(); ++r) {
    const PressureSeries& ser = series[r];
    RunSpectrum rs;
    rs.label = labels[r];
    rs.source = ser.source;
    rs.t_first = ser.t.front();
    rs.t_last = ser.t.back();
    rs.dt_data = dt_data[r];
    rs.samples = ser.t.size();
    rs.segments = welch.segments(rs.samples);
    rs.cells = ser.cells;
    for (const auto& p : ser.p) {
      rs.psd.push_back(welch.psd(p));
      rs.variance.push_back(integrate(rs.psd.back(), welch.df()));
      rs.peaks.push_back(find_peaks(rs.psd.back(), welch.df(), main_lobe_half_width(s.window), s.peaks));
    }
    for (int i = 0; i < static_cast<int>(ser.p.size()); ++i)
      for (int j = i + 1; j < static_cast<int>(ser.p.size()); ++j) {
        rs.pairs.emplace_back(i, j);
        rs.coherence.push_back(coherence(rs.psd[i], rs.psd[j], welch.csd(ser.p[i], ser.p[j])));
      }
    a.runs.push_back(std::move(rs));
  }
  return a;
}

std::string dominant_summary(const SpectrumAnalysis& a) {
  std::string out;
  const double df = a.params.fs / a.params.segment;
  for (const RunSpectrum& r : a.runs) {
    out += fmt::format("{}: t in [{:.6g}, {:.6g}] s, {} samples, {} segment(s) of {} (df = {:.6g} Hz)\n", r.label,
                       r.t_first, r.t_last, r.samples, r.segments, a.params.segment, df);
    for (size_t c = 0; c < r.cells.size(); ++c) {
      if (r.peaks[c].empty()) {
        out += fmt::format("  {}: no peak (flat spectrum)\n", r.cells[c]);
        continue;
      }
      const Peak& p = r.peaks[c][0];
      out += fmt::format("  {}: dominant {:.6g} Hz (interpolated {:.6g} Hz), PSD {:.4g} Pa^2/Hz, band power {:.4g} Pa^2 "
                         "= {:.1f} % of the variance {:.4g} Pa^2\n",
                         r.cells[c], p.f, p.f_interp, p.psd, p.band_power,
                         r.variance[c] > 0 ? 100 * p.band_power / r.variance[c] : 0.0, r.variance[c]);
    }
  }
  return out;
}

SpectrumAnalysis spectrum_report(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                 const SpectrumSettings& s, const std::string& out_dir) {
  SpectrumAnalysis a = analyse_runs(run_dirs, labels, s);
  write_spectrum_outputs(a, out_dir);
  return a;
}

}  // namespace cgdem::scaling
