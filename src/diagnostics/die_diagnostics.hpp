// Die-filling diagnostics (the observables of the paper, docs/model.md, section 6), read from
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
//   mass in the shoe  solid mass of the parcels whose centre lies inside the cavity's
//                     footprint (moving with the shoe) above the table top [kg]
//   air paths         the air leaving the die, as the volume flux up through the z-face
//                     plane at (or just below) the table top, over the die mouth, split by what lies
//                     above each face at that moment: the cavity (air that must cross the
//                     shoe's powder), the shoe's walls (air that can only leave through the
//                     shoe-table gap) and nothing (the mouth open to the room); the cavity's
//                     footprint is widened by one cell, the width over which the immersed
//                     boundary smears its walls' inner faces; each
//                     sum E_face w dx^2 [m^3/s] (positive: out of the die)
//   bubbles           air enclosed by powder (fluid/bubbles.hpp, eps >= diagnostics.eps_bubble):
//                     their number, total and largest volume, the largest one's centroid
//                     height and top, the bubbles' volume above the table top (risen into
//                     the shoe) [m^3, m]; and the air sealed by walls alone [m^3]
//   shoe surface      shoe_surface.csv, every diagnostics.surface_interval: over bins of the
//                     cavity's length (diagnostics.surface_bins, in the shoe's frame), the
//                     solid height (solid volume of the bin's parcels / bin area: the height
//                     the bed would have at packing 1) and the surface (the top z + r of the
//                     highest 2 % of the bin's parcels) [m]; a splash lifts the surface
//                     while the solid height stays
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "fluid/bubbles.hpp"
#include "fluid/fluid_state.hpp"
#include "geometry/die_filling.hpp"
#include "io/archive.hpp"
#include "io/csv_series.hpp"
#include "particles/particles.hpp"

namespace cgdem::diagnostics {

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
  double eps_bubble = 0.9;      // void fraction from which a cell counts as air (bubbles)
  double surface_interval = 5e-3;  // [s] between profiles of shoe_surface.csv
  int surface_bins = 10;        // bins over the cavity length
  std::vector<PressureCell> cells;
};

// [diagnostics] (enabled by default when [walls.die_filling] exists):
//   interval, rate_window, impact_band, impact_window, eps_bubble, surface_interval, surface_bins,
//   [[diagnostics.pressure_cell]] name/min/max
// (default cells A, B, C: see diagnostics/die_diagnostics.cpp).
DiagnosticsSpec read_diagnostics(Config& cfg);

struct DiagnosticsRow {
  double t = 0, mass_in_die = 0, transfer_rate = 0;
  std::vector<double> pressure;  // per cell, NaN without air
  long impacts = 0;              // parcels that have reached the floor so far
  double mass_in_shoe = 0;       // [kg]
  // Air paths out of the die [m^3/s] and bubbles (NaN without air; bubbles NaN when the
  // wall fractions are not given, as over MPI ranks).
  double q_cavity, q_walls, q_open;
  double bubbles, v_bubbles, v_bubble_max, z_bubble, z_bubble_top, v_bubbles_shoe, v_sealed;
  DiagnosticsRow();
};

// Volume fluxes of air out of the die through the mouth plane (see above) [m^3/s].
struct PathFlux {
  double cavity = 0, walls = 0, open = 0;
};

class DieDiagnostics {
 public:
  DieDiagnostics(DiagnosticsSpec spec, std::vector<double> species_mass, std::vector<double> species_diameter);

  // Every fluid step (or every ~0.1 ms in vacuum): impacts and the mass history. `horizon`:
  // the time to the next call [s] (0: record only the parcels already inside the band).
  void observe(double t, const Particles& p, double horizon = 0);
  // A row for diagnostics.csv (air may be null).
  // alpha_cell (the cells' wall fractions) enables the bubble census.
  DiagnosticsRow row(double t, const Particles& p, const fluid::FluidState* air, const fluid::FluidParams* fp,
                     const fluid::Field* alpha_cell = nullptr) const;
  // The bubble census of a row (bubbles, their volumes, the largest one's height, the
  // sealed air) from the air of the whole grid and its cells' wall fractions; nothing when
  // alpha_cell is empty (before the first fluid step).
  void count_bubbles(DiagnosticsRow& r, const fluid::FluidState& air, const fluid::Field& alpha_cell,
                     const fluid::FluidParams& fp) const;
  // The air paths' fluxes over the z-faces of `air` (the whole grid or one block: the sums
  // of the blocks add up, each face counted by the block that owns it, k < nz).
  PathFlux path_fluxes(const fluid::FluidState& air, double t) const;
  // shoe_surface.csv: its columns (io/csv_series.hpp) and the rows of one profile at time t.
  io::CsvColumns surface_columns() const;
  std::string surface_rows(double t, const Particles& p) const;
  double surface_interval() const { return spec_.surface_interval; }
  // The shoe's displacement along x at time t [m].
  double shoe_offset(double t) const;
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
  // diagnostics.csv: its columns (name with SI unit, unit, description; one p_<cell>_Pa per
  // pressure cell) and one row (no trailing newline).
  io::CsvColumns csv_columns() const;
  std::string csv_line(const DiagnosticsRow& r) const;
  // impacts.csv: its columns and rows (one per parcel that has reached the floor).
  static io::CsvColumns impact_columns();
  std::string impact_rows() const;

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
  // The cavity's interior at time t (moved with the shoe); a point "in" it lies inside its
  // footprint above the table top (also above the cavity's rim: a splash still counts).
  struct Cavity {
    Vec3 lo, hi;
    bool holds_column(const Vec3& x) const;
  };
  Cavity cavity_at(double t) const;
  double mass_in_shoe(const Particles& p, double t) const;

  DiagnosticsSpec spec_;
  geometry::Motion shoe_motion_;
  std::vector<double> mass_, diameter_;
  double band_ = 0;
  std::vector<uint8_t> hit_;                  // by parcel id
  std::vector<Impact> impacts_;
  struct MassSample {
    double t, mass;
  };
  std::vector<MassSample> history_;  // M(t) for the rate
};

}  // namespace cgdem::diagnostics
