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
//   peaks.csv      run,cell,rank,f_Hz,f_interp_Hz,psd_Pa2_per_Hz,band_power_Pa2,variance_fraction,
//                  background_Pa2_per_Hz,level_Pa2_per_Hz,ratio_to_level: the significant peaks only
//   background.csv f_Hz, then <label>:<cell>:background and <label>:<cell>:level per run and
//                  cell: the fitted AR(1) spectrum and its significance level (Pa^2/Hz)
//   spectrum.md    parameters, resolution, segments, window correction, the red-noise fit,
//                  the significant peaks (or "no significant peak"), coherence
//   psd.png, coherence.png when python3 with matplotlib is found (scaling/plot_spectrum.py)
// every file written atomically. Below: the pressure spectra section of `cgdem scale`.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "scaling/spectrum.hpp"
#include "scaling/spectrum_significance.hpp"
#include "scaling/spectrum_series.hpp"

namespace cgdem::scaling {

struct SpectrumSettings {
  Window window = Window::hann;
  Detrend detrend = Detrend::mean;
  std::string segment;             // "N" samples or "Ts" seconds (e.g. "0.128s"); empty: automatic
  double overlap = 0.5;            // fraction of a segment, [0, 1)
  std::optional<double> from, to;  // time range, s
  std::vector<std::string> cells;  // empty: every p_ column of the first run
  double dt = 0;                   // > 0: resample every run onto this interval, s
  int peaks = 3;                   // significant peaks listed per cell, at most
  double confidence = 0.95;        // level of the red-noise test (spectrum_significance.hpp), (0, 1)
  bool pointwise = false;          // test each bin at `confidence` instead of the global (Sidak) level
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
  double dof = 0;                              // nu of the Welch estimate (S3)
  std::vector<Ar1Fit> ar1;                     // [cell] red-noise fit (S2)
  // [cell][bin] (S1) and (S4), Pa^2/Hz: the pointwise level, the global one, and `level`, the
  // one peaks are tested against (the global level unless settings.pointwise).
  std::vector<std::vector<double>> background, pointwise_level, global_level, level;
  int tested_bins = 0;           // M of (S4): the bins searched for peaks
  double bin_confidence = 0;     // the per-bin confidence of `level`
  std::vector<std::vector<Peak>> peaks;        // [cell] significant peaks, largest first (may be empty)
  std::vector<Peak> largest;                   // [cell] largest local maximum from lowest_peak_bin on (bin -1: none)
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
// The same for series already read (read_pressure_series), one label each.
SpectrumAnalysis analyse_series(std::vector<PressureSeries> series, const std::vector<std::string>& labels,
                                const SpectrumSettings& s);

// Writes the files listed above into `dir` (created). Returns a note on the PNG (written,
// or why it was skipped).
std::string write_spectrum_outputs(const SpectrumAnalysis& a, const std::string& dir);

// One line per run and cell: the dominant significant frequency, its PSD, band power and
// ratio to the level, or "no significant peak" and how far the largest maximum stays below.
std::string dominant_summary(const SpectrumAnalysis& a);

// analyse_runs + write_spectrum_outputs: the entry point for `cgdem scale`.
SpectrumAnalysis spectrum_report(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                 const SpectrumSettings& s, const std::string& out_dir);

// ---- The pressure spectra of a coarse-graining study (`cgdem scale`, docs/scaling.md) ----
//
// The runs' series from t0 on go through ONE estimator with the defaults of `cgdem
// spectrum` (Hann, 50 % overlap, mean removed per segment, the automatic segment of the
// shortest run), so every run has the same fs and segment length L and the spectra share
// the bins f_m = m fs / L. When a run's output times are not uniform (the 0.1 % rule of
// spectrum_series.hpp) or the runs are sampled at different intervals, every run is
// resampled linearly onto the first readable run's median interval, and `resampled_why`
// says why. Never throws on a run's data: a run that cannot be analysed (no folder or
// diagnostics.csv, no sample from t0 on, too few samples for the estimator) is left out
// with the reason; if none is left, `not_applicable` says so.
struct PressureSpectra {
  std::string not_applicable;         // non-empty: why there are no spectra at all
  std::vector<std::string> left_out;  // "<run>: <reason>"
  double resampled_dt = 0;            // s; > 0 when resampled onto this interval
  std::string resampled_why;
  SpectrumAnalysis analysis;          // the analysed runs, in the given order
};
PressureSpectra analyse_pressure_spectra(const std::vector<std::string>& run_dirs,
                                         const std::vector<std::string>& labels, double t0);

// The dominant significant peak (rank 1; NaN fields when the cell has none) of each run and
// cell against the reference run on the shared bins: the frequency offset in bins (interpolated frequencies), and the relative deviations
// (x - x_ref) / x_ref of the band power of the run's own peak, of the power in the bins of
// the reference's peak (the same bins for both runs: a peak that moved away reads -100 %),
// and of the variance. NaN where the reference run, its cell or a peak is missing.
struct SpectrumDeviation {
  std::string run, cell;
  double f = NAN, f_interp = NAN;                                      // Hz
  double band_power = NAN, power_in_ref_band = NAN, variance = NAN;    // Pa^2
  double offset_bins = NAN, band_power_dev = NAN, ref_band_dev = NAN, variance_dev = NAN;
};
std::vector<SpectrumDeviation> spectrum_deviations(const SpectrumAnalysis& a, const std::string& reference);

// The "## Pressure spectra" Markdown section: the estimator, the shared bins, one row per
// run and cell with its deviations from `reference`, the runs left out; or why there are
// no spectra.
std::string pressure_spectra_section(const PressureSpectra& p, const std::vector<SpectrumDeviation>& d, double t0,
                                     const std::string& reference);

// DIR/spectrum/ (write_spectrum_outputs: psd.csv with f_Hz then <run>:<cell> side by side,
// coherence.csv, peaks.csv, spectrum.md; no PNG, plot_scale.py draws the overlay) and
// DIR/pressure_spectra.csv (the rows of `d`), all written atomically; nothing when
// p.not_applicable is set.
void write_pressure_spectra(const PressureSpectra& p, const std::vector<SpectrumDeviation>& d, const std::string& dir);

// All of the above for `cgdem scale` (labels[0] is the reference, l = 1): analyses, writes
// into report_dir, prints one line per run and cell ("spectrum <run> <cell>: ...") and
// returns the section. Also declared in scale_report.hpp.
std::string scale_pressure_spectra(const std::vector<std::string>& run_dirs, const std::vector<std::string>& labels,
                                   double t0, const std::string& report_dir);

}  // namespace cgdem::scaling
