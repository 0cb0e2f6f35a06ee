// analyse_runs: the runs' pressure series through one Welch estimator (spectrum_report.hpp);
// below it, the pressure spectra section of `cgdem scale` (analyse_pressure_spectra ...).
#include "scaling/spectrum_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
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
  const std::vector<std::string> labels = run_labels(run_dirs, given_labels);
  std::vector<PressureSeries> read;
  for (const std::string& dir : run_dirs) read.push_back(read_pressure_series(dir));
  return analyse_series(std::move(read), labels, s);
}

namespace {

// The settings and the series' labels checked (one label per series, overlap in [0, 1), at
// least one peak, confidence in (0, 1)).
void check_settings(const std::vector<PressureSeries>& read, const std::vector<std::string>& labels,
                    const SpectrumSettings& s) {
  if (read.empty()) throw Error("spectrum: no run given");
  if (labels.size() != read.size())
    throw Error(fmt::format("spectrum: {} label(s) for {} series", labels.size(), read.size()));
  if (!(s.overlap >= 0 && s.overlap < 1)) throw Error(fmt::format("--overlap: {} is not in [0, 1)", s.overlap));
  if (s.peaks < 1) throw Error(fmt::format("--peaks: {} (at least 1)", s.peaks));
  if (!(s.confidence > 0 && s.confidence < 1))
    throw Error(fmt::format("--confidence: {} is not in (0, 1) (e.g. 0.95)", s.confidence));
}

// The series over the selected range and cells (those of the first run unless --cells gives
// them), on a uniform grid: checked (all runs at one interval), or resampled onto --dt.
// Writes each run's own sampling interval into dt_data; returns the series and their dt.
std::pair<std::vector<PressureSeries>, double> uniform_series(std::vector<PressureSeries>& read,
                                                              const std::vector<std::string>& labels,
                                                              const SpectrumSettings& s, std::vector<double>& dt_data) {
  std::vector<PressureSeries> series;
  std::vector<std::string> cells = s.cells;
  for (PressureSeries& whole : read) {
    PressureSeries raw = select(whole, cells, s.from, s.to);
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
  return {std::move(series), dt};
}

// The spectra of one run's series: per cell the Welch PSD, its variance, the red-noise
// background and the significance levels, the significant peaks; per pair of cells the
// coherence.
RunSpectrum run_spectrum(const PressureSeries& ser, const std::string& label, double dt_data, const Welch& welch,
                         const SpectrumAnalysis& a, const SpectrumSettings& s) {
  RunSpectrum rs;
  rs.label = label;
  rs.source = ser.source;
  rs.t_first = ser.t.front();
  rs.t_last = ser.t.back();
  rs.dt_data = dt_data;
  rs.samples = ser.t.size();
  rs.segments = welch.segments(rs.samples);
  rs.cells = ser.cells;
  rs.dof = welch_dof(window_coefficients(a.params.window, a.params.segment), a.params.overlap, rs.segments);
  for (const auto& p : ser.p) {
    rs.psd.push_back(welch.psd(p));
    rs.variance.push_back(integrate(rs.psd.back(), welch.df()));
    // The red-noise background of this series and its level (spectrum_significance.hpp).
    rs.ar1.push_back(fit_ar1(p, s.detrend));
    rs.background.push_back(ar1_spectrum(rs.ar1.back(), a.f, a.params.fs));
    rs.tested_bins = welch.bins() - lowest_peak_bin(s.window);
    rs.bin_confidence = s.pointwise ? s.confidence : global_confidence(s.confidence, rs.tested_bins);
    rs.pointwise_level.push_back(significance_level(rs.background.back(), rs.dof, s.confidence, a.params.segment));
    rs.global_level.push_back(significance_level(rs.background.back(), rs.dof,
                                                 global_confidence(s.confidence, rs.tested_bins), a.params.segment));
    rs.level.push_back(s.pointwise ? rs.pointwise_level.back() : rs.global_level.back());
    Peak largest;
    rs.peaks.push_back(significant_peaks(rs.psd.back(), rs.background.back(), rs.level.back(), welch.df(),
                                         main_lobe_half_width(s.window), s.peaks, &largest));
    rs.largest.push_back(largest);
  }
  for (int i = 0; i < static_cast<int>(ser.p.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(ser.p.size()); ++j) {
      rs.pairs.emplace_back(i, j);
      rs.coherence.push_back(coherence(rs.psd[i], rs.psd[j], welch.csd(ser.p[i], ser.p[j])));
    }
  return rs;
}

}  // namespace

// The steps above, then the Welch parameters from the shortest series.
SpectrumAnalysis analyse_series(std::vector<PressureSeries> read, const std::vector<std::string>& labels,
                                const SpectrumSettings& s) {
  check_settings(read, labels, s);
  // Series: selected range and cells, on a uniform grid (checked, or resampled onto --dt).
  std::vector<double> dt_data;
  auto [series, dt] = uniform_series(read, labels, s, dt_data);

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

  for (size_t r = 0; r < series.size(); ++r)
    a.runs.push_back(run_spectrum(series[r], labels[r], dt_data[r], welch, a, s));
  return a;
}

std::string dominant_summary(const SpectrumAnalysis& a) {
  std::string out;
  const double df = a.params.fs / a.params.segment;
  const double pct = 100 * a.settings.confidence;
  for (const RunSpectrum& r : a.runs) {
    out += fmt::format("{}: t in [{:.6g}, {:.6g}] s, {} samples, {} segment(s) of {} (df = {:.6g} Hz, nu = {:.3g}); "
                       "peaks sought from bin {} ({:.6g} Hz) on, above the {} {:g} % level of AR(1) red noise\n",
                       r.label, r.t_first, r.t_last, r.samples, r.segments, a.params.segment, df, r.dof,
                       lowest_peak_bin(a.params.window), lowest_peak_bin(a.params.window) * df,
                       a.settings.pointwise ? "pointwise" : fmt::format("global (over {} bins)", r.tested_bins), pct);
    for (size_t c = 0; c < r.cells.size(); ++c) {
      const Ar1Fit& fit = r.ar1[c];
      if (r.peaks[c].empty()) {
        const Peak& m = r.largest[c];
        out += fmt::format("  {}: no significant peak (AR(1) phi = {:.4f}, variance {:.4g} Pa^2", r.cells[c], fit.phi,
                           fit.variance);
        out += m.bin < 0 ? "; no local maximum in the searched bins)\n"
                         : fmt::format("; the largest local maximum, {:.6g} Hz, is {:.2f} of the level)\n", m.f,
                                       m.ratio);
        continue;
      }
      const Peak& p = r.peaks[c][0];
      out += fmt::format("  {}: dominant {:.6g} Hz (interpolated {:.6g} Hz), PSD {:.4g} Pa^2/Hz = {:.3g} x the {:g} % "
                         "level (AR(1) phi = {:.4f}), band power {:.4g} Pa^2 = {:.1f} % of the variance {:.4g} Pa^2\n",
                         r.cells[c], p.f, p.f_interp, p.psd, p.ratio, pct, fit.phi, p.band_power,
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

// ---- The pressure spectra of `cgdem scale` ----

namespace {

std::string num(double v, int digits) { return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : "n/a"; }
std::string g10(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : "nan"; }
std::string percent(double v) { return std::isfinite(v) ? fmt::format("{:+.1f} %", 100 * v) : "n/a"; }
double relative_deviation(double x, double ref) { return ref != 0 ? (x - ref) / ref : NAN; }

// A run's pressure series from t0 on, or (nullopt) the reason it has none.
std::optional<PressureSeries> pressure_series_from(const std::string& dir, double t0, std::string* why) {
  try {
    return select(read_pressure_series(dir), {}, t0, {});
  } catch (const Error& e) {
    *why = e.what();
    return std::nullopt;
  }
}

// 0 when every series is uniformly sampled (the 0.1 % rule) at the first one's interval,
// so that one estimator gives them the same bins as they are; otherwise the first series'
// median interval, to resample every run onto (`why` says what was found).
double resampling_interval(const std::vector<PressureSeries>& series, const std::vector<std::string>& labels,
                           std::string* why) {
  const double dt = uniform_interval(series[0], INFINITY);  // the median interval
  for (size_t r = 0; r < series.size(); ++r) {
    try {
      const double d = uniform_interval(series[r]);
      if (std::abs(d - dt) <= 1e-3 * dt) continue;
      *why = fmt::format("{} is sampled every {:.6g} s, {} every {:.6g} s", labels[0], dt, labels[r], d);
    } catch (const Error& e) {
      *why = labels[r] + ": " + e.what();
    }
    return dt;
  }
  return 0;
}

// Whether the estimator's segment fits the series (the automatic segment: 8 segments of at
// least 8 samples); the reason otherwise.
bool long_enough_for_welch(const PressureSeries& ser, const SpectrumSettings& st, std::string* why) {
  const double dt = st.dt > 0 ? st.dt : uniform_interval(ser, INFINITY);
  const size_t n = st.dt > 0 ? resample(ser, st.dt).t.size() : ser.t.size();
  try {
    segment_samples(st.segment, dt, n, st.overlap);
    return true;
  } catch (const Error&) {
    const int needed = static_cast<int>(std::ceil(8 * (1 + 7 * (1 - st.overlap)) - 1e-9));
    *why = fmt::format("{} samples of p from t = {:.6g} to {:.6g} s, too few for one segment of the default estimator "
                       "(8 segments of at least 8 samples at {:.0f} % overlap need {} samples)",
                       n, ser.t.front(), ser.t.back(), 100 * st.overlap, needed);
    return false;
  }
}

std::string spectra_method(const PressureSpectra& p, double t0) {
  const WelchParams& w = p.analysis.params;
  std::string t = fmt::format(
      "Welch spectra of the gauge pressure at the cells (diagnostics.csv, columns p_<cell>) from t0 = {:g} s on, "
      "with the defaults of `cgdem spectrum` (docs/spectra.md): {} window, {:.0f} % overlap, detrending \"{}\" of "
      "each segment, segment L = {} samples = {} s (the largest power of two giving 8 segments of the shortest "
      "run). Every run goes through this one estimator (fs = {} Hz, the same L), so the runs share the bins "
      "f_m = m fs / L (df = {} Hz, up to {} Hz): `spectrum/psd.csv` holds them side by side on that one frequency "
      "column. A peak is the largest local maximum of the PSD from bin {} (f >= {} Hz; bins 0 and 1 hold the mean "
      "and whatever varies over a segment length, a transient pulse, and the peak's left neighbour must lie outside "
      "the window's DC lobe) that exceeds the {:g} % level of an AR(1) "
      "red-noise background fitted to the run's own series (docs/spectra.md); a cell without one reads \"no "
      "significant peak\".",
      t0, to_string(w.window), 100.0 * w.overlap / w.segment, to_string(w.detrend), w.segment,
      num(w.segment / w.fs, 4), num(w.fs, 6), num(w.fs / w.segment, 4), num(p.analysis.f.back(), 6), lowest_peak_bin(w.window),
      num(lowest_peak_bin(w.window) * w.fs / w.segment, 4), 100 * p.analysis.settings.confidence);
  if (p.resampled_dt > 0)
    t += fmt::format(" The series were resampled linearly onto dt = {:g} s (the first run's median interval) because "
                     "{}.",
                     p.resampled_dt, p.resampled_why);
  return t + "\n\n";
}

int segments_of(const SpectrumAnalysis& a, const std::string& run) {
  for (const auto& r : a.runs)
    if (r.label == run) return r.segments;
  return 0;
}

std::string spectra_table(const PressureSpectra& p, const std::vector<SpectrumDeviation>& dev, const std::string& ref) {
  std::string t = fmt::format(
      "Dominant significant peak of each cell (interpolated frequency in brackets), its band power (sum P df over the main lobe), the power of the run in the bins of {0}'s peak, and "
      "the variance (integral of the PSD); deviations from {0} as (x - x_ref) / x_ref, frequency offsets in bins:\n\n"
      "| run | cell | segments K | dominant f (Hz) | offset vs {0} (bins) | band power (Pa^2) | vs {0} | "
      "power in {0}'s band (Pa^2) | vs {0} | variance (Pa^2) | vs {0} |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n",
      ref);
  for (const SpectrumDeviation& d : dev) {
    const std::string offset = std::isfinite(d.offset_bins) ? fmt::format("{:+.2f}", d.offset_bins) : "n/a";
    const std::string f = std::isfinite(d.f) ? num(d.f, 5) + " (" + num(d.f_interp, 5) + ")" : "no significant peak";
    t += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", d.run, d.cell,
                     segments_of(p.analysis, d.run), f, offset, num(d.band_power, 4),
                     percent(d.band_power_dev), num(d.power_in_ref_band, 4), percent(d.ref_band_dev),
                     num(d.variance, 4), percent(d.variance_dev));
  }
  return t;
}

void print_spectra(const PressureSpectra& p, const std::vector<SpectrumDeviation>& dev) {
  if (!p.not_applicable.empty()) fmt::print("spectrum: not applicable: {}\n", p.not_applicable);
  for (const auto& w : p.left_out) fmt::print("spectrum: left out {}\n", w);
  for (const SpectrumDeviation& d : dev)
    if (!std::isfinite(d.f))
      fmt::print("spectrum {} {}: no significant peak, variance {:.4g} Pa^2 ({})\n", d.run, d.cell, d.variance,
                 percent(d.variance_dev));
    else
      fmt::print("spectrum {} {}: dominant {:.6g} Hz (offset {:.3g} bins), band power {:.4g} Pa^2 ({}), variance "
               "{:.4g} Pa^2 ({})\n",
               d.run, d.cell, d.f_interp, d.offset_bins, d.band_power, percent(d.band_power_dev), d.variance,
               percent(d.variance_dev));
}

}  // namespace

PressureSpectra analyse_pressure_spectra(const std::vector<std::string>& run_dirs,
                                         const std::vector<std::string>& labels, double t0) {
  if (labels.size() != run_dirs.size())
    throw Error(fmt::format("pressure spectra: {} label(s) for {} run folder(s)", labels.size(), run_dirs.size()));
  PressureSpectra p;
  SpectrumSettings st;  // the defaults of `cgdem spectrum`
  st.from = t0;
  st.plot = false;  // plot_scale.py draws the overlay
  std::vector<PressureSeries> series;
  std::vector<std::string> readable_labels;
  for (size_t r = 0; r < run_dirs.size(); ++r) {
    std::string why;
    std::optional<PressureSeries> ser = pressure_series_from(run_dirs[r], t0, &why);
    if (!ser) {
      p.left_out.push_back(labels[r] + ": " + why);
      continue;
    }
    series.push_back(std::move(*ser));
    readable_labels.push_back(labels[r]);
  }
  if (series.empty()) {
    p.not_applicable = "no run has a readable pressure series";
    return p;
  }
  st.dt = p.resampled_dt = resampling_interval(series, readable_labels, &p.resampled_why);
  std::vector<PressureSeries> usable;  // read once: the estimator takes them as they are
  std::vector<std::string> names;
  for (size_t r = 0; r < series.size(); ++r) {
    std::string why;
    if (long_enough_for_welch(series[r], st, &why)) {
      usable.push_back(std::move(series[r]));
      names.push_back(readable_labels[r]);
    } else {
      p.left_out.push_back(readable_labels[r] + ": " + why);
    }
  }
  if (usable.empty()) {
    p.not_applicable = "no run is long enough for the estimator";
    return p;
  }
  try {
    p.analysis = analyse_series(std::move(usable), names, st);
  } catch (const Error& e) {
    p.not_applicable = std::string("the spectra could not be estimated: ") + e.what();
  }
  return p;
}

std::vector<SpectrumDeviation> spectrum_deviations(const SpectrumAnalysis& a, const std::string& reference) {
  std::vector<SpectrumDeviation> out;
  const RunSpectrum* ref = nullptr;
  for (const RunSpectrum& r : a.runs)
    if (r.label == reference) ref = &r;
  const double df = a.params.segment > 0 ? a.params.fs / a.params.segment : NAN;
  const int h = main_lobe_half_width(a.params.window);
  for (const RunSpectrum& r : a.runs)
    for (size_t c = 0; c < r.cells.size(); ++c) {
      SpectrumDeviation d;
      d.run = r.label;
      d.cell = r.cells[c];
      d.variance = r.variance[c];
      if (!r.peaks[c].empty()) {
        d.f = r.peaks[c][0].f;
        d.f_interp = r.peaks[c][0].f_interp;
        d.band_power = r.peaks[c][0].band_power;
      }
      const bool same_cell = ref && c < ref->cells.size() && ref->cells[c] == r.cells[c];
      if (same_cell) d.variance_dev = relative_deviation(d.variance, ref->variance[c]);
      if (!same_cell || ref->peaks[c].empty()) {  // no significant reference peak: no band to compare
        out.push_back(d);
        continue;
      }
      const Peak& rp = ref->peaks[c][0];
      d.power_in_ref_band = band_power(r.psd[c], rp.bin, h, df);
      d.offset_bins = (d.f_interp - rp.f_interp) / df;  // NaN when this run has no significant peak
      d.band_power_dev = relative_deviation(d.band_power, rp.band_power);
      d.ref_band_dev = relative_deviation(d.power_in_ref_band, rp.band_power);
      out.push_back(d);
    }
  return out;
}

std::string pressure_spectra_section(const PressureSpectra& p, const std::vector<SpectrumDeviation>& dev, double t0,
                                     const std::string& reference) {
  std::string t = "## Pressure spectra\n\n";
  if (!p.not_applicable.empty()) t += "Not applicable: " + p.not_applicable + ".\n\n";
  else t += spectra_method(p, t0) + spectra_table(p, dev, reference);
  if (!p.left_out.empty()) {
    t += "\nLeft out:\n\n";
    for (const auto& w : p.left_out) t += "* " + w + "\n";
  }
  if (p.not_applicable.empty())
    t += "\nFiles: `spectrum/psd.csv` (PSD in Pa^2/Hz, one column `<run>:<cell>` each), `spectrum/coherence.csv`, "
         "`spectrum/peaks.csv`, `spectrum/spectrum.md` (the estimator's parameters and window factors), "
         "`pressure_spectra.csv` (the table above), `pressure_psd.png` (the overlay, plot_scale.py).\n";
  return t + "\n";
}

void write_pressure_spectra(const PressureSpectra& p, const std::vector<SpectrumDeviation>& dev,
                            const std::string& dir) {
  if (!p.not_applicable.empty()) return;
  write_spectrum_outputs(p.analysis, (std::filesystem::path(dir) / "spectrum").string());
  std::string csv = "run,cell,f_Hz,f_interp_Hz,offset_bins_vs_ref,band_power_Pa2,band_power_rel_dev,"
                    "power_in_ref_band_Pa2,power_in_ref_band_rel_dev,variance_Pa2,variance_rel_dev\n";
  for (const SpectrumDeviation& d : dev)
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", d.run, d.cell, g10(d.f), g10(d.f_interp),
                       g10(d.offset_bins), g10(d.band_power), g10(d.band_power_dev), g10(d.power_in_ref_band),
                       g10(d.ref_band_dev), g10(d.variance), g10(d.variance_dev));
  io::write_file_atomic((std::filesystem::path(dir) / "pressure_spectra.csv").string(), csv);
}

std::string scale_pressure_spectra(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                   double t0, const std::string& report_dir) {
  const PressureSpectra p = analyse_pressure_spectra(run_dirs, labels, t0);
  const std::string reference = labels.empty() ? "" : labels[0];
  const std::vector<SpectrumDeviation> d = spectrum_deviations(p.analysis, reference);
  write_pressure_spectra(p, d, report_dir);
  print_spectra(p, d);
  return pressure_spectra_section(p, d, t0, reference);
}

}  // namespace cgdem::scaling
