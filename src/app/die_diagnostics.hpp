// Die-filling diagnostics (the observables of the paper, physics.md section 5), read from
// the parcels and the air while a case runs:
//
//   mass in the die   M(t) = sum of parcel masses whose centre is below the table top
//                     inside the die mouth's x-y footprint [kg]
//   transfer rate     Mdot(t) = (M(t) - M(t - w)) / w, a backward difference over the
//                     window w = diagnostics.rate_window (default 5 ms) [kg/s]
//   impacts           a parcel "impacts" the first time its lowest point comes within
//                     diagnostics.impact_band (default: a quarter of the largest parcel diameter)
//                     of the die floor under it; its downward speed on the way there is
//                     recorded. The parcels are seen only every fluid step (0.2 ms: 66 um at
//                     0.33 m/s, more than the band of a 125 um parcel, and 16 collision times),
//                     so a parcel could cross the band, hit the floor and rebound between two
//                     looks. Hence the look ahead: a parcel moving down at speed s whose gap
//                     h to the band would close within the time to the next look (horizon)
//                     is recorded now, at t + h / s, with its approach speed s; one first
//                     seen inside the band (pushed there, or with no horizon) is recorded as
//                     seen. The powder front reaches the floor at the first impact; the
//                     impact velocity of the paper is the mass-weighted mean downward speed
//                     of the impacts within diagnostics.impact_window (default 5 ms) after it.
//   pressure cells    gauge pressure averaged over the air cells whose centres lie in each
//                     configured box (A, B, C), gauge = p - p_open - rho_f g.(x - x_open)
//                     (the still-air hydrostatic pressure removed) [Pa]
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "fluid/fluid_state.hpp"
#include "geometry/die_filling.hpp"
#include "io/archive.hpp"
#include "particles/particles.hpp"

namespace cgdem::app {

struct PressureCell {
  std::string name;
  Vec3 lo, hi;  // [m]
};

struct DiagnosticsSpec {
  bool enabled = false;
  geometry::DieFillingParams die;
  double interval = 1e-4;       // [s] between rows of diagnostics.csv
  double rate_window = 5e-3;    // [s]
  double impact_band = 0;       // [m] above the floor (0: a quarter of the largest parcel diameter)
  double impact_window = 5e-3;  // [s]
  std::vector<PressureCell> cells;
};

// [diagnostics] (enabled by default when [walls.die_filling] exists):
//   interval, rate_window, impact_band, impact_window, [[diagnostics.pressure_cell]] name/min/max
// (default cells A, B, C: see die_diagnostics.cpp).
DiagnosticsSpec read_diagnostics(Config& cfg);

struct DiagnosticsRow {
  double t = 0, mass_in_die = 0, transfer_rate = 0;
  std::vector<double> pressure;  // per cell, NaN without air
  long impacts = 0;              // parcels that have reached the floor so far
};

class DieDiagnostics {
 public:
  DieDiagnostics(DiagnosticsSpec spec, std::vector<double> species_mass, std::vector<double> species_diameter);

  // Every fluid step (or every ~0.1 ms in vacuum): impacts and the mass history. `horizon`:
  // the time to the next call [s] (0: record only the parcels already inside the band).
  void observe(double t, const Particles& p, double horizon = 0);
  // A row for diagnostics.csv (air may be null).
  DiagnosticsRow row(double t, const Particles& p, const fluid::FluidState* air, const fluid::FluidParams* fp) const;
  // The pressure cells' gauge pressure summed over the cells of `air` (the whole grid, or one
  // block of `whole`) whose centres lie in each, and their count: the row's pressures are
  // the sums over all blocks divided by the counts (mean_pressures; NaN for a cell box
  // without air cells or without air).
  struct PressureSum {
    double sum = 0;
    long cells = 0;
  };
  std::vector<PressureSum> pressure_sums(const fluid::FluidState& air, const fluid::MacGrid& whole,
                                         const fluid::FluidParams& fp) const;
  std::vector<double> mean_pressures(const std::vector<PressureSum>& sums) const;
  std::string csv_header() const;
  std::string csv_line(const DiagnosticsRow& r) const;

  struct Impact {
    int64_t id;
    double t, speed_down, mass;
  };
  const std::vector<Impact>& impacts() const { return impacts_; }
  // Time of the first impact (the earliest, as look-ahead impacts are stored when seen)
  // and the mass-weighted mean downward speed within the window.
  std::optional<std::pair<double, double>> front_impact() const;

  // Checkpoint of the running state (impacts so far, mass history).
  void save(io::ArchiveWriter& w) const;
  void load(io::ArchiveReader& r);

 private:
  double mass_in_die(const Particles& p) const;
  double floor_z(double x) const;
  bool in_mouth(const Vec3& x) const;

  DiagnosticsSpec spec_;
  std::vector<double> mass_, diameter_;
  double band_ = 0;
  std::vector<uint8_t> hit_;                  // by parcel id
  std::vector<Impact> impacts_;
  struct MassSample {
    double t, mass;
  };
  std::vector<MassSample> history_;  // M(t) for the rate
};

}  // namespace cgdem::app
