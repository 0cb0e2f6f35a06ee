// The pressure spectra of the scale report (scaling/spectrum_report.hpp:
// analyse_pressure_spectra, spectrum_deviations, write_pressure_spectra,
// scale_pressure_spectra) on synthetic run
// folders whose diagnostics.csv hold on-bin sines, so that every figure has a closed form:
//   fs = 1 kHz, 513 samples from t0 = 0 (rows before t0 are left out), automatic segment
//   L = 64 (the largest power of two giving 8 segments), df = 15.625 Hz, Hann window;
//   a sine of amplitude A on bin k puts A^2/2 into the band of bins k-1..k+1 and nothing
//   outside it, so band powers and the power in the reference's band are exact to rounding.
//   l=1:  A = 2 sin at bin 10, B = 1 sin at bin 20, C = 0.5 sin at bin 5
//   l=2:  A amplitude 2 sqrt(1.1) (band power +10 %), B moved to bin 24 (offset +4 bins,
//         none of its power in l=1's band), C as l=1 (deviation 0)
// plus a run too short for the estimator (left out, named), a run without diagnostics.csv
// (left out), non-uniform output times (resampled onto the reference's interval), no run
// long enough (no spectra, no exception), and the files written. (A case without air
// reads "not applicable": scale_report.cpp, checked by the CI column collapse.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "scaling/spectrum_report.hpp"
#include "tests/io/scratch.hpp"

namespace cgdem::scaling {
namespace {

using io::test::scratch_dir;
using io::test::slurp;
using io::test::spit;

constexpr double kDt = 1e-3, kDf = 1000.0 / 64;

struct Sine {
  double amplitude, bin;
};

// RUN/diagnostics.csv with p_A, p_B, p_C = the sines, rows at t = t_first + i dt (i < n)
// with `late` added to every time from row `late_from` on (an output that waited a step).
std::string run_folder(const std::string& dir, const std::array<Sine, 3>& p, int n, double t_first = -0.064,
                       double late = 0, int late_from = 0) {
  std::filesystem::create_directories(dir);
  std::string s = "# synthetic run\nt,mass_in_die_kg,transfer_rate_kg_s,p_A,p_B,p_C\n";
  for (int i = 0; i < n; ++i) {
    const double t = t_first + i * kDt + (late_from > 0 && i >= late_from ? late : 0.0);
    s += fmt::format("{:.17g},0,0", t);
    for (const Sine& q : p)
      s += fmt::format(",{:.17g}", q.amplitude * std::sin(2 * std::numbers::pi * q.bin * kDf * t));
    s += "\n";
  }
  spit(dir + "/diagnostics.csv", s);
  return dir;
}

// The runs of a study: folders and labels, l = 1 first.
struct Runs {
  std::vector<std::string> dirs, labels;
  Runs& add(const std::string& label, const std::string& dir) {
    labels.push_back(label);
    dirs.push_back(dir);
    return *this;
  }
};

const std::array<Sine, 3> kReference{{{2.0, 10}, {1.0, 20}, {0.5, 5}}};
const std::array<Sine, 3> kCoarse{{{2.0 * std::sqrt(1.1), 10}, {1.0, 24}, {0.5, 5}}};

const SpectrumDeviation& row(const std::vector<SpectrumDeviation>& d, const std::string& run, const std::string& cell) {
  for (const auto& x : d)
    if (x.run == run && x.cell == cell) return x;
  throw std::runtime_error("no row " + run + " " + cell);
}

TEST(ScaleSpectra, DeviationsFromTheReferenceOnSharedBins) {
  const std::string dir = scratch_dir();
  // 577 rows from t = -0.064 s: 513 of them from t0 = 0 on.
  Runs runs;
  runs.add("l=1", run_folder(dir + "/l=1", kReference, 577))
      .add("l=2", run_folder(dir + "/l=2", kCoarse, 577))
      .add("simply_large_2", run_folder(dir + "/sl", kReference, 20 + 64, -0.064))
      .add("l=3", dir + "/missing");
  const PressureSpectra p = analyse_pressure_spectra(runs.dirs, runs.labels, 0.0);
  ASSERT_EQ(p.not_applicable, "");
  EXPECT_EQ(p.resampled_dt, 0.0) << p.resampled_why;
  ASSERT_EQ(p.analysis.runs.size(), 2u);
  EXPECT_EQ(p.analysis.params.segment, 64);
  EXPECT_NEAR(p.analysis.params.fs, 1000.0, 1e-9 * 1000.0);  // 1 / median interval of rounded times
  EXPECT_EQ(p.analysis.runs[0].samples, 513u);
  EXPECT_EQ(p.analysis.runs[0].segments, 15);  // K = floor((513 - 64) / 32) + 1
  ASSERT_EQ(p.left_out.size(), 2u);
  std::printf("left out: %s\nleft out: %s\n", p.left_out[0].c_str(), p.left_out[1].c_str());
  EXPECT_NE(p.left_out[0].find("l=3: spectrum: run folder"), std::string::npos);
  EXPECT_NE(p.left_out[1].find("simply_large_2: 20 samples of p from t = 0 to 0.019 s, too few for one segment"),
            std::string::npos);
  EXPECT_NE(p.left_out[1].find("need 36 samples"), std::string::npos);

  const auto d = spectrum_deviations(p.analysis, "l=1");
  ASSERT_EQ(d.size(), 6u);
  const double tol = 1e-9;  // rounding of 513-sample sums; the closed forms are exact
  const auto& a1 = row(d, "l=1", "A");
  const auto& a2 = row(d, "l=2", "A");
  const auto& b2 = row(d, "l=2", "B");
  const auto& c2 = row(d, "l=2", "C");
  std::printf("l=1 A: f %.6g Hz (want %.6g), band power %.12g Pa^2 (want 2)\n", a1.f_interp, 10 * kDf, a1.band_power);
  std::printf("l=2 A: band power deviation %.3e (want 0.1), offset %.3e bins (want 0)\n", a2.band_power_dev,
              a2.offset_bins);
  std::printf("l=2 B: offset %.6f bins (want 4), power in l=1's band deviation %.3e (want -1)\n", b2.offset_bins,
              b2.ref_band_dev);
  std::printf("l=2 C: band power deviation %.3e, variance deviation %.3e (want 0, 0)\n", c2.band_power_dev,
              c2.variance_dev);
  EXPECT_NEAR(a1.f, 10 * kDf, 1e-9 * kDf);  // bin 10 of that fs
  EXPECT_NEAR(a1.f_interp, 10 * kDf, 1e-9 * kDf);
  EXPECT_NEAR(a1.band_power, 2.0, 2.0 * tol);
  EXPECT_NEAR(a1.band_power_dev, 0.0, tol);
  EXPECT_NEAR(a1.offset_bins, 0.0, tol);
  EXPECT_NEAR(a2.band_power_dev, 0.1, tol);
  EXPECT_NEAR(a2.ref_band_dev, 0.1, tol);
  EXPECT_NEAR(a2.variance_dev, 0.1, tol);
  EXPECT_NEAR(a2.offset_bins, 0.0, tol);
  EXPECT_NEAR(b2.offset_bins, 4.0, tol);
  EXPECT_NEAR(b2.band_power_dev, 0.0, tol);
  EXPECT_NEAR(b2.ref_band_dev, -1.0, tol);
  EXPECT_NEAR(c2.band_power_dev, 0.0, tol);
  EXPECT_NEAR(c2.variance_dev, 0.0, tol);

  // Files: the spectra side by side on one frequency column, the table, the section.
  write_pressure_spectra(p, d, dir);
  const std::string psd = slurp(dir + "/spectrum/psd.csv");
  EXPECT_NE(psd.find("\nf_Hz,l=1:A,l=1:B,l=1:C,l=2:A,l=2:B,l=2:C\n"), std::string::npos);
  const std::string table = slurp(dir + "/pressure_spectra.csv");
  EXPECT_EQ(table.rfind("run,cell,f_Hz,f_interp_Hz,offset_bins_vs_ref,", 0), 0u) << table;
  EXPECT_NE(table.find("\nl=2,B,375,"), std::string::npos) << table;
  const std::string md = pressure_spectra_section(p, d, 0.0, "l=1");
  EXPECT_NE(md.find("segment L = 64 samples"), std::string::npos) << md;
  EXPECT_NE(md.find("| l=2 | B | 15 | 375 (375) | +4.00 |"), std::string::npos) << md;
  EXPECT_NE(md.find("* simply_large_2: 20 samples"), std::string::npos) << md;
}

TEST(ScaleSpectra, NonUniformOutputTimesAreResampledOntoTheReferenceInterval) {
  const std::string dir = scratch_dir();
  // l=2's outputs run 0.1 ms late from its 300th row on, as in the slab run of docs/spectra.md.
  Runs runs;
  runs.add("l=1", run_folder(dir + "/l=1", kReference, 577))
      .add("l=2", run_folder(dir + "/l=2", kReference, 577, -0.064, 1e-4, 300));
  const PressureSpectra p = analyse_pressure_spectra(runs.dirs, runs.labels, 0.0);
  ASSERT_EQ(p.not_applicable, "");
  std::printf("resampled onto %g s because %s\n", p.resampled_dt, p.resampled_why.c_str());
  EXPECT_NEAR(p.resampled_dt, kDt, 1e-15);
  EXPECT_NE(p.resampled_why.find("l=2: "), std::string::npos);
  EXPECT_NE(p.resampled_why.find("sampling is not uniform"), std::string::npos);
  ASSERT_EQ(p.analysis.runs.size(), 2u);
  const auto d = spectrum_deviations(p.analysis, "l=1");
  // l=1 is uniform: resampling it changes nothing. l=2's late samples sit 0.1 dt after the
  // grid, so each grid value is 0.1 x[j-1] + 0.9 x[j]: a sine of angular step w dt keeps its
  // frequency and bin, attenuated by g = |0.1 + 0.9 exp(i w dt)|. Its band power can only
  // drop, by at most 1 - g^2 (every segment late); about half the segments are late here.
  for (const char* c : {"A", "B", "C"}) {
    const auto& x = row(d, "l=2", c);
    const double w_dt = 2 * std::numbers::pi * x.f / 1000.0;
    const double g2 = 0.82 + 0.18 * std::cos(w_dt);  // |0.1 + 0.9 e^{i w dt}|^2
    std::printf("l=2 %s: offset %.3e bins (tolerance 0.5), band power deviation %.4f in [%.4f, 0] (+-1e-3)\n", c,
                x.offset_bins, x.band_power_dev, -(1 - g2));
    EXPECT_EQ(x.f, row(d, "l=1", c).f);
    EXPECT_LT(std::fabs(x.offset_bins), 0.5);
    EXPECT_LE(x.band_power_dev, 1e-3);
    EXPECT_GE(x.band_power_dev, -(1 - g2) - 1e-3);
    EXPECT_NEAR(row(d, "l=1", c).band_power, c[0] == 'A' ? 2.0 : c[0] == 'B' ? 0.5 : 0.125, 1e-9);
  }
  EXPECT_NE(pressure_spectra_section(p, d, 0.0, "l=1").find("resampled linearly onto dt = 0.001 s"), std::string::npos);
}

TEST(ScaleSpectra, RunsTooShortGiveAClearSectionNotAnException) {
  const std::string dir = scratch_dir();
  Runs runs;
  runs.add("l=1", run_folder(dir + "/a", kReference, 64 + 30)).add("l=2", run_folder(dir + "/b", kReference, 64 + 10));
  const std::string md = scale_pressure_spectra(runs.dirs, runs.labels, 0.0, dir);
  std::printf("%s", md.c_str());
  EXPECT_NE(md.find("Not applicable: no run is long enough for the estimator."), std::string::npos);
  EXPECT_NE(md.find("* l=1: 30 samples of p from t = 0 to 0.029 s, too few for one segment"), std::string::npos);
  EXPECT_NE(md.find("* l=2: 10 samples"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/pressure_spectra.csv"));  // nothing written
  const PressureSpectra p = analyse_pressure_spectra(runs.dirs, runs.labels, 0.0);
  EXPECT_TRUE(spectrum_deviations(p.analysis, "l=1").empty());

  // A t0 after every sample: named, not thrown.
  const PressureSpectra late = analyse_pressure_spectra(runs.dirs, runs.labels, 1.0);
  EXPECT_EQ(late.not_applicable, "no run has a readable pressure series");
  ASSERT_EQ(late.left_out.size(), 2u);
  EXPECT_NE(late.left_out[0].find("l=1: --from/--to:"), std::string::npos) << late.left_out[0];
}

TEST(ScaleSpectra, EntryPointWritesTheSectionAndFiles) {
  const std::string dir = scratch_dir();
  Runs runs;
  runs.add("l=1", run_folder(dir + "/l=1", kReference, 577)).add("l=2", run_folder(dir + "/l=2", kCoarse, 577));
  const std::string md = scale_pressure_spectra(runs.dirs, runs.labels, 0.0, dir + "/report");
  EXPECT_EQ(md.rfind("## Pressure spectra\n\nWelch spectra", 0), 0u) << md;
  for (const char* f : {"spectrum/psd.csv", "spectrum/coherence.csv", "spectrum/peaks.csv", "spectrum/spectrum.md",
                        "pressure_spectra.csv"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/report/" + f)) << f;
  EXPECT_EQ(io::test::count_temporaries(dir + "/report"), 0);
}

}  // namespace
}  // namespace cgdem::scaling
