// Spectra of the cell pressures of one or several runs, overlaid on one frequency grid:
// what `cgdem spectrum` writes and what `cgdem scale` calls for its ratios.
//
//   const SpectrumAnalysis a = spectrum_report({"out/l=1", "out/l=2"}, {"l=1", "l=2"}, settings, "report/spectrum");
//
// reads RUN/diagnostics.csv of every run (spectrum_series.hpp), cuts the --from/--to range,
// checks uniform sampling (or resamples onto --dt), estimates with one Welch estimator
// (spectrum.hpp: same fs, segment, overlap, window for every run, so the columns share f):
//   psd.csv        f_Hz, then <label>:<cell> per run and cell         (Pa^2/Hz, one-sided)
//   coherence.csv  f_Hz, then <label>:<cell>-<cell> per run and pair  (magnitude-squared)
//   peaks.csv      run,cell,rank,f_Hz,f_interp_Hz,psd_Pa2_per_Hz,band_power_Pa2,variance_fraction
//   spectrum.md    parameters, resolution, segments, window correction, dominant frequencies
//   psd.png, coherence.png when python3 with matplotlib is found (scaling/plot_spectrum.py)
// every file written atomically.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scaling/spectrum.hpp"

namespace cgdem::scaling {

struct SpectrumSettings {
  Window window = Window::hann;
  Detrend detrend = Detrend::mean;
  std::string segment;             // "N" samples or "Ts" seconds (e.g. "0.128s"); empty: automatic
  double overlap = 0.5;            // fraction of a segment, [0, 1)
  std::optional<double> from, to;  // time range, s
  std::vector<std::string> cells;  // empty: every p_ column of the first run
  double dt = 0;                   // > 0: resample every run onto this interval, s
  int peaks = 3;                   // dominant frequencies per cell
  bool plot = true;                // try the PNG (never fails without python3/matplotlib)
};

struct RunSpectrum {
  std::string label, source;
  double t_first = 0, t_last = 0, dt_data = 0;  // selected span and its own (median) interval
  size_t samples = 0;
  int segments = 0;
  std::vector<std::string> cells;
  std::vector<std::vector<double>> psd;        // [cell][bin], Pa^2/Hz
  std::vector<double> variance;                // [cell] integral of the PSD, Pa^2 (W4)
  std::vector<std::pair<int, int>> pairs;      // cell index pairs (i < j)
  std::vector<std::vector<double>> coherence;  // [pair][bin]
  std::vector<std::vector<Peak>> peaks;        // [cell], largest first
};

struct SpectrumAnalysis {
  SpectrumSettings settings;
  WelchParams params;  // fs, L, overlap in samples, window, detrend
  WindowFactors factors;
  std::vector<double> f;
  std::vector<RunSpectrum> runs;
};

// The segment length in samples: "N" (a whole number of samples) or "Ts" (seconds, rounded
// to the nearest sample). Empty: the largest power of two giving at least 8 segments of the
// shortest run (n samples) at the given overlap. Error naming --segment otherwise.
int segment_samples(const std::string& spec, double dt, size_t n, double overlap);

// Reads and analyses the runs (labels: one per run, or empty for the folder names).
SpectrumAnalysis analyse_runs(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                              const SpectrumSettings& s);

// Writes the files listed above into `dir` (created). Returns a note on the PNG (written,
// or why it was skipped).
std::string write_spectrum_outputs(const SpectrumAnalysis& a, const std::string& dir);

// One line per run and cell: the dominant frequency, its PSD and band power.
std::string dominant_summary(const SpectrumAnalysis& a);

// analyse_runs + write_spectrum_outputs: the entry point for `cgdem scale`.
SpectrumAnalysis spectrum_report(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                 const SpectrumSettings& s, const std::string& out_dir);

}  // namespace cgdem::scaling
