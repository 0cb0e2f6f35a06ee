// write_spectrum_outputs: the CSV files, the Markdown report and the optional PNG
// (formats in spectrum_report.hpp). Every file goes through io::write_file_atomic; the
// plot script writes its PNGs to a temporary name and renames them.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "io/atomic_file.hpp"
#include "scaling/plot_script.hpp"
#include "scaling/spectrum_report.hpp"

namespace cgdem::scaling {
namespace {

std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : "nan"; }

std::string header_comment(const SpectrumAnalysis& a) {
  const WelchParams& p = a.params;
  std::string segs;
  for (const auto& r : a.runs) segs += fmt::format("{}{}={}", segs.empty() ? "" : ";", r.label, r.segments);
  return fmt::format(
      "# cgdem {} spectrum: fs {} Hz, df {} Hz, segment {} samples, overlap {}, window {}, detrend {}; one-sided, "
      "integral over f = variance; peaks from bin {} ({} Hz) above the {} level of AR(1) red noise ({}); segments {}\n",
      kGitRevision, num(p.fs), num(p.fs / p.segment), p.segment, p.overlap, to_string(p.window), to_string(p.detrend),
      lowest_peak_bin(p.window), num(lowest_peak_bin(p.window) * p.fs / p.segment), num(a.settings.confidence),
      a.settings.pointwise ? "pointwise" : "global", segs);
}

std::string psd_csv(const SpectrumAnalysis& a) {
  std::string s = header_comment(a) + "f_Hz";
  for (const auto& r : a.runs)
    for (const auto& c : r.cells) s += fmt::format(",{}:{}", r.label, c);
  s += '\n';
  for (size_t m = 0; m < a.f.size(); ++m) {
    s += num(a.f[m]);
    for (const auto& r : a.runs)
      for (const auto& p : r.psd) s += fmt::format(",{}", num(p[m]));
    s += '\n';
  }
  return s;
}

std::string coherence_csv(const SpectrumAnalysis& a) {
  std::string s = header_comment(a) + "f_Hz";
  for (const auto& r : a.runs)
    for (const auto& [i, j] : r.pairs) s += fmt::format(",{}:{}-{}", r.label, r.cells[i], r.cells[j]);
  s += '\n';
  for (size_t m = 0; m < a.f.size(); ++m) {
    s += num(a.f[m]);
    for (const auto& r : a.runs)
      for (const auto& c : r.coherence) s += fmt::format(",{}", num(c[m]));
    s += '\n';
  }
  return s;
}

std::string peaks_csv(const SpectrumAnalysis& a) {
  std::string s = header_comment(a) +
                  "run,cell,rank,f_Hz,f_interp_Hz,psd_Pa2_per_Hz,band_power_Pa2,variance_fraction,"
                  "background_Pa2_per_Hz,level_Pa2_per_Hz,ratio_to_level\n";
  for (const auto& r : a.runs)
    for (size_t c = 0; c < r.cells.size(); ++c)
      for (size_t k = 0; k < r.peaks[c].size(); ++k) {
        const Peak& p = r.peaks[c][k];
        s += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r.label, r.cells[c], k + 1, num(p.f), num(p.f_interp),
                         num(p.psd), num(p.band_power), num(r.variance[c] > 0 ? p.band_power / r.variance[c] : NAN),
                         num(p.background), num(p.level), num(p.ratio));
      }
  return s;
}

// The AR(1) background and its significance level per run and cell, on the PSD's bins.
std::string background_csv(const SpectrumAnalysis& a) {
  std::string s = header_comment(a) + "f_Hz";
  for (const auto& r : a.runs)
    for (const auto& c : r.cells)
      s += fmt::format(",{0}:{1}:background,{0}:{1}:level,{0}:{1}:pointwise_level,{0}:{1}:global_level", r.label, c);
  s += '\n';
  for (size_t m = 0; m < a.f.size(); ++m) {
    s += num(a.f[m]);
    for (const auto& r : a.runs)
      for (size_t c = 0; c < r.cells.size(); ++c)
        s += fmt::format(",{},{},{},{}", num(r.background[c][m]), num(r.level[c][m]), num(r.pointwise_level[c][m]),
                         num(r.global_level[c][m]));
    s += '\n';
  }
  return s;
}

// The red-noise fit and the significance test, one row per run and cell.
std::string significance_md(const SpectrumAnalysis& a) {
  const WelchParams& p = a.params;
  const double df = p.fs / p.segment, pct = 100 * a.settings.confidence;
  std::string md = fmt::format(
      "\n## Peaks against red noise\n\nA peak is reported when it is a local maximum of the PSD from bin {0} on "
      "(f >= {1} Hz: bin 0 is the removed mean and bin 1, f = 1/segment = {2} Hz, holds whatever varies over a "
      "segment, a trend or a single pulse; the peak's left neighbour must lie outside the window's DC lobe, which "
      "the per-segment mean removal lowers: bin 3 for Hann, 2 for rect) and its PSD exceeds the {3:g} % level of a red-noise background: the "
      "spectrum of an AR(1) process with the series' variance and lag-1 autocorrelation phi (detrended series, "
      "bias-corrected), times the chi-square quantile Q_nu({4:g}) / nu for the Welch estimate's equivalent degrees "
      "of freedom nu (docs/spectra.md). {5}\n\n",
      lowest_peak_bin(p.window), num(lowest_peak_bin(p.window) * df), num(df), pct, a.settings.confidence,
      a.settings.pointwise
          ? fmt::format("The test is pointwise (--pointwise): in pure red noise about {:g} % of the bins exceed the "
                        "level, so a spectrum of many bins shows some exceedances by chance.",
                        100 - pct)
          : fmt::format("The level is global: each of the M bins searched is tested at the confidence {:g}^(1/M) "
                        "(Sidak), so that pure red noise shows no peak at all in {:g} % of the series (the pointwise "
                        "level, exceeded by {:g} % of the bins of pure red noise, is in background.csv).",
                        a.settings.confidence, pct, 100 - pct));
  md += "| run | cell | samples | variance (Pa^2) | r1 | phi | se(phi) | nu | bins searched M | per-bin confidence | "
        "level / background | significant peaks |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : a.runs)
    for (size_t c = 0; c < r.cells.size(); ++c) {
      const Ar1Fit& f = r.ar1[c];
      const int mid = static_cast<int>(r.level[c].size()) / 2;  // an interior bin: the factor Q_nu/nu
      std::string verdict = fmt::format("{}", r.peaks[c].size());
      if (r.peaks[c].empty()) {
        verdict = "no significant peak";
        if (r.largest[c].bin >= 0)
          verdict += fmt::format(" (largest local maximum {:.6g} Hz at {:.2f} of the level)", r.largest[c].f,
                                 r.largest[c].ratio);
      }
      md += fmt::format("| {} | {} | {} | {:.4g} | {:.4f} | {:.4f} | {:.4f} | {:.3g} | {} | {:.6f} | {:.3f} | {} |\n",
                        r.label, r.cells[c], f.n, f.variance, f.r1, f.phi, f.phi_se, r.dof, r.tested_bins,
                        r.bin_confidence, r.level[c][mid] / r.background[c][mid], verdict);
    }
  return md;
}

// The title and the table of the estimate's parameters.
std::string parameters_md(const SpectrumAnalysis& a) {
  const WelchParams& p = a.params;
  const WindowFactors& w = a.factors;
  const SpectrumSettings& s = a.settings;
  const double df = p.fs / p.segment;
  std::string md = fmt::format("# Pressure spectra\n\ncgdem {}. Welch estimate (docs/spectra.md).\n\n", kGitRevision);
  md += "| parameter | value |\n|---|---|\n";
  md += fmt::format("| time range (--from, --to) | {} to {} |\n", s.from ? num(*s.from) + " s" : "first sample",
                    s.to ? num(*s.to) + " s" : "last sample");
  md += fmt::format("| sampling | fs = {} Hz (dt = {} s{}) |\n", num(p.fs), num(1 / p.fs),
                    s.dt > 0 ? ", linearly resampled" : "");
  md += fmt::format("| segment | {} samples = {} s |\n", p.segment, num(p.segment / p.fs));
  md += fmt::format("| overlap | {} samples ({:.0f} %) |\n", p.overlap, 100.0 * p.overlap / p.segment);
  md += fmt::format("| frequency resolution | df = fs / L = {} Hz; f up to {} Hz |\n", num(df), num(a.f.back()));
  md += fmt::format("| window | {} (periodic) |\n", to_string(p.window));
  md += fmt::format("| detrending of each segment | {} |\n", to_string(p.detrend));
  md += fmt::format(
      "| window correction | PSD divided by fs sum w^2 (power gain sum w^2 / L = {:.4f}): the integral of the PSD "
      "is the variance. Coherent gain sum w / L = {:.4f}; ENBW = {:.4f} bins = {} Hz: a peak's bin reads "
      "A^2/2 / ENBW for a sine of amplitude A, its band power A^2/2 |\n",
      w.power_gain, w.coherent_gain, w.enbw_bins, num(w.enbw_hz));
  md += fmt::format("| peaks | local maxima from bin {} (f >= {} Hz) above the {:g} % level of AR(1) red noise (below) |\n",
                    lowest_peak_bin(p.window), num(lowest_peak_bin(p.window) * df), 100 * s.confidence);
  return md;
}

// One row per run: its source, samples, time range and segments.
std::string runs_md(const SpectrumAnalysis& a) {
  std::string md;
  md += "\n| run | source | samples | t first (s) | t last (s) | segments K | coherence bias ~1/K |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : a.runs)
    md += fmt::format("| {} | `{}` | {} | {} | {} | {} | {:.3f} |\n", r.label, r.source, r.samples, num(r.t_first),
                      num(r.t_last), r.segments, 1.0 / r.segments);
  return md;
}

// The significant peaks of every run and cell (or "no significant peak").
std::string peaks_md(const SpectrumAnalysis& a) {
  const WelchParams& p = a.params;
  const SpectrumSettings& s = a.settings;
  std::string md;
  md += fmt::format("\n## Significant peaks\n\nBand power: sum of PSD df over the {} bins around the maximum; "
                    "ratio: PSD over the {:g} % level at the bin.\n\n",
                    2 * main_lobe_half_width(p.window) + 1, 100 * s.confidence);
  md += "| run | cell | rank | f (Hz) | f interpolated (Hz) | PSD (Pa^2/Hz) | ratio to level | band power (Pa^2) | of the "
        "variance | variance (Pa^2) |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : a.runs)
    for (size_t c = 0; c < r.cells.size(); ++c) {
      if (r.peaks[c].empty())
        md += fmt::format("| {} | {} | — | no significant peak | | | | | | {:.4g} |\n", r.label, r.cells[c],
                          r.variance[c]);
      for (size_t k = 0; k < r.peaks[c].size(); ++k) {
        const Peak& pk = r.peaks[c][k];
        md += fmt::format("| {} | {} | {} | {:.6g} | {:.6g} | {:.4g} | {:.3g} | {:.4g} | {:.1f} % | {:.4g} |\n",
                          r.label, r.cells[c], k + 1, pk.f, pk.f_interp, pk.psd, pk.ratio, pk.band_power,
                          r.variance[c] > 0 ? 100 * pk.band_power / r.variance[c] : 0.0, r.variance[c]);
      }
    }
  return md;
}

// Per run and pair of cells: the largest coherence, its frequency and the mean over f > 0.
std::string coherence_md(const SpectrumAnalysis& a) {
  std::string md;
  md += "\n## Coherence\n\n| run | cells | largest | at f (Hz) | mean over f > 0 |\n|---|---|---|---|---|\n";
  for (const auto& r : a.runs)
    for (size_t q = 0; q < r.pairs.size(); ++q) {
      const auto& c = r.coherence[q];
      size_t best = 1;
      double mean = 0;
      int n = 0;
      for (size_t m = 1; m < c.size(); ++m) {
        if (!std::isfinite(c[m])) continue;
        if (!std::isfinite(c[best]) || c[m] > c[best]) best = m;
        mean += c[m];
        ++n;
      }
      md += fmt::format("| {} | {}-{} | {:.3f} | {:.6g} | {:.3f} |\n", r.label, r.cells[r.pairs[q].first],
                        r.cells[r.pairs[q].second], c[best], a.f[best], n ? mean / n : NAN);
    }
  return md;
}

std::string markdown(const SpectrumAnalysis& a, const std::string& png_note) {
  std::string md = parameters_md(a) + runs_md(a);
  md += significance_md(a);
  md += peaks_md(a);
  md += coherence_md(a);
  md += fmt::format("\nFiles: `psd.csv`, `background.csv`, `coherence.csv`, `peaks.csv`{}\n", png_note);
  return md;
}

// Runs scaling/plot_spectrum.py on `dir`; returns the note for the report and the log.
std::string plot(const std::string& dir) {
  const std::string why = run_plot_script("plot_spectrum.py", dir);
  return why.empty() ? "" : "no PNG: " + why;
}

}  // namespace

std::string write_spectrum_outputs(const SpectrumAnalysis& a, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("--output: cannot create '{}': {}", dir, ec.message()));
  const auto path = [&](const char* name) { return (std::filesystem::path(dir) / name).string(); };
  io::write_file_atomic(path("psd.csv"), psd_csv(a));
  io::write_file_atomic(path("coherence.csv"), coherence_csv(a));
  io::write_file_atomic(path("peaks.csv"), peaks_csv(a));
  io::write_file_atomic(path("background.csv"), background_csv(a));
  const std::string note = a.settings.plot ? plot(dir) : "no PNG: plotting switched off";
  const std::string png = note.empty() ? ", `psd.png`, `coherence.png`.\n\n![PSD](psd.png)\n\n![coherence](coherence.png)"
                                       : fmt::format(" ({}).", note);
  io::write_file_atomic(path("spectrum.md"), markdown(a, png));
  return note.empty() ? fmt::format("wrote {}/psd.png, coherence.png", dir) : note;
}

}  // namespace cgdem::scaling
