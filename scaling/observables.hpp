// Observables of one run, for the side-by-side comparison of a coarse-graining study.
//
//   * metrics.csv (io/metrics.hpp): every scalar the run wrote (front time, impact velocity,
//     fill mass, peaks of the transfer rate and of the pressures at A, B, C ...);
//   * diagnostics.csv (die filling): the mass-transfer-rate curve and the gauge pressure at
//     each measurement cell as time series; their peaks (time, height) and the final fill
//     mass are derived here too, so the comparison does not depend on metrics.csv;
//   * the last particle snapshot: the final pile-height profile along x,
//       h(x_i) = mean over the y-columns j that hold solid of max_{p in (i,j)} (z_p + d_p/2) - z_lo
//     on columns of width b (the same b for every run of a study: twice the largest parcel
//     diameter, so a column holds a parcel of any run), 0 where no solid is; the run-out
//     x_95 (the x below which 95 % of the solid volume lies, from the domain's x_lo) and the
//     centre of mass (from the domain's lower corner).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "scaling/series.hpp"
#include "scaling/scale_runs.hpp"

namespace cgdem::scaling {

struct RunObservables {
  std::map<std::string, double> scalars;  // name (with SI unit suffix) -> value
  Series transfer_rate;                   // kg/s (empty without diagnostics)
  std::map<std::string, Series> pressure;  // "p_A" -> Pa
  std::vector<double> profile_x, profile_h;  // m
  double final_time = 0;                      // s, of the snapshot the profile comes from
};

struct ProfileSpec {
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0, z_lo = 0;
  double bin = 0;  // m
};

// Pure part: the profile, run-out and centre of mass of a set of parcels.
void pile_observables(const std::vector<Vec3>& x, const std::vector<double>& d, const ProfileSpec& s,
                      RunObservables& out);

// Curves and their peaks from t0 on (metrics.csv, when present, holds the run's own peaks:
// over t >= 0, see app/run_metrics.hpp).
RunObservables read_observables(const std::string& dir, const ProfileSpec& s, double t0);

}  // namespace cgdem::scaling
