#include "diagnostics/die_diagnostics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cgdem::diagnostics {

DiagnosticsSpec read_diagnostics(Config& cfg) {
  DiagnosticsSpec d;
  Section root = cfg.root();
  const bool die = root.has("walls") && root.section("walls").has("die_filling");
  if (!die) {
    if (root.has("diagnostics"))
      root.section("diagnostics").fail("rate_window", "die-filling diagnostics need a [walls.die_filling] section");
    return d;
  }
  d.enabled = true;
  d.die = geometry::read_die_filling(root.section("walls").section("die_filling"));
  Section s(&cfg, "diagnostics");
  d.interval = s.number_or("interval", d.interval, Range::positive());
  d.rate_window = s.number_or("rate_window", d.rate_window, Range::positive());
  d.impact_band = s.number_or("impact_band", 0.0, Range::non_negative());
  d.impact_window = s.number_or("impact_window", d.impact_window, Range::positive());
  d.eps_bubble = s.number_or("eps_bubble", d.eps_bubble, Range::open_closed(0, 1));
  d.surface_interval = s.number_or("surface_interval", d.surface_interval, Range::positive());
  d.surface_bins = static_cast<int>(s.integer_or("surface_bins", d.surface_bins, Range::closed(1, 1000)));
  auto cells = s.sections("pressure_cell");
  for (const Section& c : cells) {
    PressureCell pc{c.string("name"), c.vec3("min"), c.vec3("max")};
    for (int a = 0; a < 3; ++a)
      if (!(pc.hi[a] > pc.lo[a])) c.fail("max", "must exceed min on every axis");
    d.cells.push_back(pc);
  }
  if (cells.empty()) {
    // Defaults (the paper does not give the positions): boxes of 2.4 x 2.4 x 1.2 mm
    // (4 x 4 x 2 cells of the 0.6 mm grid) on the die's mid-plane in y. A: shallow section, just above its floor;
    // B: deep section, just above its floor; C: deep section, just below the table top
    // (where the shoe's powder enters).
    const auto& p = d.die;
    const double yc = p.mouth_y0 + 0.5 * p.mouth_width, h = 0.6e-3;
    const double split = p.mouth_x0 + p.step_fraction * p.mouth_length;
    const bool shallow_left = p.die_type == 1;
    const double xs = shallow_left ? 0.5 * (p.mouth_x0 + split) : 0.5 * (split + p.mouth_x0 + p.mouth_length);
    const double xd = shallow_left ? 0.5 * (split + p.mouth_x0 + p.mouth_length) : 0.5 * (p.mouth_x0 + split);
    const double zs = p.table_top - p.shallow_depth, zd = p.table_top - p.deep_depth;
    auto box = [&](const char* n, double x, double z) {
      return PressureCell{n, {x - 2 * h, yc - 2 * h, z}, {x + 2 * h, yc + 2 * h, z + 2 * h}};
    };
    d.cells = {box("A", xs, zs + h), box("B", xd, zd + h), box("C", xd, p.table_top - 3 * h)};
  }
  return d;
}

DieDiagnostics::DieDiagnostics(DiagnosticsSpec spec, std::vector<double> species_mass,
                               std::vector<double> species_diameter)
    : spec_(std::move(spec)), shoe_motion_(spec_.die.shoe_motion()), mass_(std::move(species_mass)), diameter_(std::move(species_diameter)) {
  band_ = spec_.impact_band;
  if (band_ <= 0) band_ = 0.25 * *std::max_element(diameter_.begin(), diameter_.end());
}

DiagnosticsRow::DiagnosticsRow() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  q_cavity = q_walls = q_open = nan;
  bubbles = v_bubbles = v_bubble_max = z_bubble = z_bubble_top = v_bubbles_shoe = v_sealed = nan;
}

double DieDiagnostics::shoe_offset(double t) const { return shoe_motion_.displacement(t).x; }

DieDiagnostics::Cavity DieDiagnostics::cavity_at(double t) const {
  const Vec3 off{shoe_offset(t), 0, 0};
  return {spec_.die.cavity_lo() + off, spec_.die.cavity_hi() + off};
}

bool DieDiagnostics::Cavity::holds_column(const Vec3& x) const {
  return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z > lo.z;
}

double DieDiagnostics::mass_in_shoe(const Particles& p, double t) const {
  const Cavity c = cavity_at(t);
  double m = 0;
  for (size_t i = 0; i < p.size(); ++i)
    if (c.holds_column(p.x[i])) m += mass_[p.species[i]];
  return m;
}

PathFlux DieDiagnostics::path_fluxes(const fluid::FluidState& air, double t) const {
  PathFlux q;
  const auto& d = spec_.die;
  const auto& g = air.grid;
  // The z-face plane at the table top, or just below it when the top is off the grid, in
  // this grid's own indices.
  const double z_plane = g.dx * std::floor((d.table_top - g.origin.z) / g.dx * (1 + 1e-12)) + g.origin.z;
  const int k = static_cast<int>(std::lround((z_plane - g.origin.z) / g.dx));
  if (k < 0 || k >= g.nz) return q;  // not in this block (k = nz is the upper block's face)
  const double w = d.shoe_wall;
  const Cavity cav = cavity_at(t);
  const Vec3 c0 = cav.lo, c1 = cav.hi;
  const double area = g.dx * g.dx;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Vec3 f = g.face_centre(2, i, j, k);
      if (f.x < d.mouth_x0 || f.x > d.mouth_x0 + d.mouth_length || f.y < d.mouth_y0 ||
          f.y > d.mouth_y0 + d.mouth_width)
        continue;
      const double flux = 0.5 * (air.eps(i, j, k) + air.eps(i, j, k - 1)) * air.w(i, j, k) * area;
      // The volume-weighted forcing smears a wall's face over one cell: air rising within a
      // cell of the cavity's inner faces enters the cavity, and is counted with it.
      const double s = g.dx;
      const bool cavity = f.x >= c0.x - s && f.x <= c1.x + s && f.y >= c0.y - s && f.y <= c1.y + s;
      const bool shoe = f.x >= c0.x - w && f.x <= c1.x + w && f.y >= c0.y - w && f.y <= c1.y + w;
      (cavity ? q.cavity : shoe ? q.walls : q.open) += flux;
    }
  return q;
}

io::CsvColumns DieDiagnostics::surface_columns() const {
  return {{"t_s", "s", "time of the profile"},
          {"bin", "1", fmt::format("bin index along the cavity's length, 0 .. {}", spec_.surface_bins - 1)},
          {"x_cavity_m", "m", "bin centre from the cavity's rear wall (in the shoe's frame)"},
          {"x_m", "m", "bin centre in the domain's frame"},
          {"solid_height_m", "m", "solid volume of the bin's parcels over the bin's area (the bed's height at packing 1)"},
          {"surface_m", "m", "bed surface above the table top: the lowest top z + r of the bin's highest 2 % of parcels (nan: empty bin)"},
          {"parcels", "1", "parcels in the bin"}};
}

std::string DieDiagnostics::surface_rows(double t, const Particles& p) const {
  const auto& d = spec_.die;
  const int nb = spec_.surface_bins;
  const Cavity c = cavity_at(t);
  const Vec3 lo = c.lo, hi = c.hi;
  const double len = hi.x - lo.x, bin = len / nb;
  std::vector<double> solid(nb, 0.0);
  std::vector<std::vector<double>> tops(nb);
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.x[i];
    if (!c.holds_column(x)) continue;
    const int b = std::min(nb - 1, static_cast<int>((x.x - lo.x) / bin));
    const double r = p.radius[i];
    solid[b] += 4.0 / 3.0 * M_PI * r * r * r;
    tops[b].push_back(x.z + r);
  }
  std::string s;
  const double area = bin * (hi.y - lo.y);
  for (int b = 0; b < nb; ++b) {
    auto& v = tops[b];
    double surface = std::numeric_limits<double>::quiet_NaN();
    if (!v.empty()) {
      // The lowest of the highest 2 % (at least one parcel).
      const size_t top = std::max<size_t>(1, static_cast<size_t>(std::ceil(0.02 * v.size())));
      std::nth_element(v.begin(), v.end() - top, v.end());
      surface = *(v.end() - top) - d.table_top;
    }
    s += fmt::format("{:.9g},{},{:.9g},{:.9g},{:.9g},{:.9g},{}\n", t, b, (b + 0.5) * bin, lo.x + (b + 0.5) * bin,
                     solid[b] / area, surface, v.size());
  }
  return s;
}

bool DieDiagnostics::in_mouth(const Vec3& x) const {
  const auto& p = spec_.die;
  return x.x >= p.mouth_x0 && x.x <= p.mouth_x0 + p.mouth_length && x.y >= p.mouth_y0 &&
         x.y <= p.mouth_y0 + p.mouth_width && x.z < p.table_top;
}

double DieDiagnostics::floor_z(double x) const {
  const auto& p = spec_.die;
  const double split = p.mouth_x0 + p.step_fraction * p.mouth_length;
  const bool shallow = (p.die_type == 1) == (x < split);
  return p.table_top - (shallow ? p.shallow_depth : p.deep_depth);
}

double DieDiagnostics::mass_in_die(const Particles& p) const {
  double m = 0;
  for (size_t i = 0; i < p.size(); ++i)
    if (in_mouth(p.x[i])) m += mass_[p.species[i]];
  return m;
}

void DieDiagnostics::observe(double t, const Particles& p, double horizon) {
  if (!spec_.enabled) return;
  for (size_t i = 0; i < p.size(); ++i) {
    const auto id = static_cast<size_t>(p.id[i]);
    if (id >= hit_.size()) hit_.resize(id + 1, 0);
    if (hit_[id] || !in_mouth(p.x[i])) continue;
    const double gap = p.x[i].z - p.radius[i] - (floor_z(p.x[i].x) + band_);  // to the band
    const double s = -p.v[i].z;                                                // downward speed
    if (gap < 0) {
      hit_[id] = 1;
      impacts_.push_back({p.id[i], t, s, mass_[p.species[i]]});
    } else if (s > 0 && gap < s * horizon) {  // reaches the band before the next look
      hit_[id] = 1;
      impacts_.push_back({p.id[i], t + gap / s, s, mass_[p.species[i]]});
    }
  }
  history_.push_back({t, mass_in_die(p)});
}

std::optional<std::pair<double, double>> DieDiagnostics::front_impact() const {
  if (impacts_.empty()) return std::nullopt;
  double t0 = impacts_.front().t;
  for (const auto& im : impacts_) t0 = std::min(t0, im.t);
  double mv = 0, m = 0;
  for (const auto& im : impacts_)
    if (im.t <= t0 + spec_.impact_window) mv += im.mass * im.speed_down, m += im.mass;
  return std::make_pair(t0, mv / m);
}

DiagnosticsRow DieDiagnostics::row(double t, const Particles& p, const fluid::FluidState* air,
                                   const fluid::FluidParams* fp, const fluid::Field* alpha_cell) const {
  DiagnosticsRow r;
  r.t = t;
  r.mass_in_die = mass_in_die(p);
  r.mass_in_shoe = mass_in_shoe(p, t);
  if (air) {
    const PathFlux q = path_fluxes(*air, t);
    r.q_cavity = q.cavity, r.q_walls = q.walls, r.q_open = q.open;
  }
  if (air && alpha_cell && fp) count_bubbles(r, *air, *alpha_cell, *fp);
  r.impacts = static_cast<long>(impacts_.size());
  // Backward difference over the window, from the recorded history.
  r.transfer_rate = 0;
  if (!history_.empty()) {
    auto it = std::lower_bound(history_.begin(), history_.end(), t - spec_.rate_window,
                               [](const MassSample& h, double v) { return h.t < v - 1e-12; });
    if (it != history_.end() && t - it->t > 0.5 * spec_.rate_window)
      r.transfer_rate = (r.mass_in_die - it->mass) / (t - it->t);
  }
  const std::vector<PressureSum> sums = air ? pressure_sums(*air, air->grid, *fp) : std::vector<PressureSum>{};
  r.pressure = mean_pressures(sums);
  return r;
}

void DieDiagnostics::count_bubbles(DiagnosticsRow& r, const fluid::FluidState& air, const fluid::Field& alpha_cell,
                                   const fluid::FluidParams& fp) const {
  if (alpha_cell.empty()) return;  // before the first fluid step
  const fluid::BubbleCensus b =
      fluid::find_bubbles(air.grid, air.eps, alpha_cell, fp.bc, spec_.eps_bubble, 1, spec_.die.table_top);
  r.bubbles = static_cast<double>(b.bubbles.size());
  r.v_bubbles = b.total_volume();
  r.v_sealed = b.sealed_volume;
  r.v_bubbles_shoe = b.total_volume_above();
  r.v_bubble_max = b.largest() ? b.largest()->volume : 0.0;
  if (b.largest()) r.z_bubble = b.largest()->centroid.z, r.z_bubble_top = b.largest()->z_top;
}

std::vector<DieDiagnostics::PressureSum> DieDiagnostics::pressure_sums(const fluid::FluidState& air, const fluid::MacGrid& whole,
                                                       const fluid::FluidParams& fp) const {
  std::vector<PressureSum> out;
  const auto& g = air.grid;
  // Reference: the still-air pressure, p_open at the top open side, hydrostatic below.
  const Vec3 top = whole.origin + whole.dx * Vec3{0.5 * whole.nx, 0.5 * whole.ny, double(whole.nz)};
  for (const auto& c : spec_.cells) {
    // Only the index range the box can touch (one cell of margin against rounding); the
    // exact containment test below decides.
    auto range = [&](double lo, double hi, double o, int n, int& a, int& b) {
      a = std::max(0, static_cast<int>(std::floor((lo - o) / g.dx - 0.5)) - 1);
      b = std::min(n - 1, static_cast<int>(std::ceil((hi - o) / g.dx - 0.5)) + 1);
    };
    int i0, i1, j0, j1, k0, k1;
    range(c.lo.x, c.hi.x, g.origin.x, g.nx, i0, i1);
    range(c.lo.y, c.hi.y, g.origin.y, g.ny, j0, j1);
    range(c.lo.z, c.hi.z, g.origin.z, g.nz, k0, k1);
    PressureSum ps;
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Vec3 x = g.cell_centre(i, j, k);
          if (x.x < c.lo.x || x.x > c.hi.x || x.y < c.lo.y || x.y > c.hi.y || x.z < c.lo.z || x.z > c.hi.z) continue;
          ps.sum += air.p(i, j, k) - fp.bc[5].pressure - fp.rho * dot(fp.gravity, x - top);
          ++ps.cells;
        }
    out.push_back(ps);
  }
  return out;
}

std::vector<double> DieDiagnostics::mean_pressures(const std::vector<PressureSum>& sums) const {
  std::vector<double> out;
  for (size_t c = 0; c < spec_.cells.size(); ++c) {
    const bool have = c < sums.size() && sums[c].cells > 0;
    out.push_back(have ? sums[c].sum / sums[c].cells : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

void DieDiagnostics::save(io::ArchiveWriter& w) const {
  w.tag("diagnostics");
  w.put_vector(hit_), w.put_vector(impacts_), w.put_vector(history_);
}

void DieDiagnostics::load(io::ArchiveReader& r) {
  r.tag("diagnostics");
  r.get_vector(hit_), r.get_vector(impacts_), r.get_vector(history_);
}

io::CsvColumns DieDiagnostics::csv_columns() const {
  io::CsvColumns c = {
      {"t_s", "s", "time"},
      {"mass_in_die_kg", "kg", "solid mass of the parcels whose centre lies in the die (below the table top, in the mouth)"},
      {"transfer_rate_kg_s", "kg/s",
       fmt::format("mass transfer rate into the die, backward difference of mass_in_die_kg over {:g} s", spec_.rate_window)},
      {"impacts", "1", "parcels that have reached the die floor so far"}};
  for (const auto& cell : spec_.cells)
    c.push_back({"p_" + cell.name + "_Pa", "Pa",
                 fmt::format("gauge pressure (still-air hydrostatic removed) averaged over the air cells in box {} "
                             "[{:g} {:g} {:g}] .. [{:g} {:g} {:g}] m (nan without air)",
                             cell.name, cell.lo.x, cell.lo.y, cell.lo.z, cell.hi.x, cell.hi.y, cell.hi.z)});
  const io::CsvColumns rest = {
      {"mass_in_shoe_kg", "kg", "solid mass of the parcels above the table top inside the cavity's footprint (moving with the shoe)"},
      {"Q_cavity_m3_s", "m^3/s", "air volume flux out of the die through the mouth plane under the cavity (nan without air)"},
      {"Q_shoe_walls_m3_s", "m^3/s", "the same under the shoe's walls (air leaving through the shoe-table gap)"},
      {"Q_open_mouth_m3_s", "m^3/s", "the same where the mouth is open to the room"},
      {"bubbles", "1", "number of bubbles (air enclosed by powder; nan without air or over MPI ranks)"},
      {"V_bubbles_m3", "m^3", "total bubble volume"},
      {"V_bubble_max_m3", "m^3", "volume of the largest bubble"},
      {"z_bubble_m", "m", "centroid height of the largest bubble"},
      {"z_bubble_top_m", "m", "top of the largest bubble"},
      {"V_bubbles_shoe_m3", "m^3", "bubble volume above the table top (risen into the shoe)"},
      {"V_sealed_m3", "m^3", "air sealed by walls alone"}};
  c.insert(c.end(), rest.begin(), rest.end());
  return c;
}

std::string DieDiagnostics::csv_line(const DiagnosticsRow& r) const {
  std::string s = fmt::format("{:.9g},{:.9g},{:.9g},{}", r.t, r.mass_in_die, r.transfer_rate, r.impacts);
  for (double p : r.pressure) s += fmt::format(",{:.9g}", p);
  for (double v : {r.mass_in_shoe, r.q_cavity, r.q_walls, r.q_open, r.bubbles, r.v_bubbles, r.v_bubble_max, r.z_bubble,
                   r.z_bubble_top, r.v_bubbles_shoe, r.v_sealed})
    s += fmt::format(",{:.9g}", v);
  return s;
}

io::CsvColumns DieDiagnostics::impact_columns() {
  return {{"id", "1", "parcel id"},
          {"t_s", "s", "time the parcel's lowest point reached the impact band above the die floor"},
          {"speed_down_m_s", "m/s", "its downward speed on the way there"},
          {"mass_kg", "kg", "its solid mass"}};
}

std::string DieDiagnostics::impact_rows() const {
  std::string rows;
  for (const auto& im : impacts_) rows += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", im.id, im.t, im.speed_down, im.mass);
  return rows;
}

}  // namespace cgdem::diagnostics
