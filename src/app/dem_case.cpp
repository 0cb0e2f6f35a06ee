#include "app/dem_case.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "geometry/die_filling.hpp"
#include "geometry/scene_config.hpp"
#include "io/particle_csv.hpp"
#include "io/particle_h5.hpp"
#include "particles/particle_io.hpp"

namespace cgdem::app {

namespace {

// Upper bounds of the physical keys (stated in the messages through Range::describe and
// in the key documentation, dem_case.hpp).
constexpr double kMaxDiameter = 1.0;       // m, d_original
constexpr double kMaxRatio = 100.0;        // coarse-grain ratio l
constexpr double kMaxDensity = 1e5;        // kg/m^3 (the densest solids are ~2.3e4)
constexpr double kMaxCoordinate = 1e3;     // m, |domain.min|, |domain.max|
constexpr double kMaxGravity = 1e5;        // m/s^2 per component
constexpr double kMaxTime = 1e6;           // s, |time.start|, |time.end|
constexpr double kMaxSteps = 1e12;         // DEM steps from time.start to time.end
constexpr long kMaxParcels = 100000000;    // parcels of one [[particles.insert]]
constexpr double kMaxCells = 2e8;          // neighbour-search cells over the domain
constexpr double kMaxPacking = 0.7405;     // pi/sqrt(18): no packing of equal spheres is denser

int species_index(const std::vector<Species>& sp, const Section& s, const std::string& key) {
  std::string name = s.string(key);
  for (size_t i = 0; i < sp.size(); ++i)
    if (sp[i].name == name) return static_cast<int>(i);
  std::vector<std::string> names;
  for (const auto& x : sp) names.push_back(x.name);
  s.fail(key, fmt::format("unknown species \"{}\" (defined: {})", name, fmt::join(names, ", ")));
}

// The largest parcel diameter of the species [m].
double largest_diameter(const std::vector<Species>& species) {
  double dmax = 0;
  for (const auto& sp : species) dmax = std::max(dmax, sp.diameter());
  return dmax;
}

// [particles] seed, skin and [[particles.species]]: writes c.seed, c.dem.skin, c.species
// (at least one, names distinct); the skin at most 10 largest diameters (beyond a few
// diameters the neighbour lists become quadratic).
void read_species(const Section& ps, DemCase& c) {
  c.seed = static_cast<uint64_t>(ps.integer_or("seed", 1, Range::non_negative()));
  c.dem.skin = ps.number_or("skin", 0.0, Range::closed(0, 1));
  auto specs = ps.sections("species");
  if (specs.empty()) ps.fail("species", "at least one [[particles.species]] is required");
  for (const Section& s : specs) {
    Species sp;
    sp.name = s.string("name");
    sp.d_original = s.number("d_original", Range::open_closed(0, kMaxDiameter));
    sp.ratio = s.number_or("ratio", 1.0, Range::closed(1.0, kMaxRatio));
    sp.density = s.number("density", Range::open_closed(0, kMaxDensity));
    for (const auto& other : c.species)
      if (other.name == sp.name) s.fail("name", fmt::format("species \"{}\" is defined twice", sp.name));
    c.species.push_back(sp);
  }
  const double dmax = largest_diameter(c.species);
  if (c.dem.skin > 10 * dmax)
    ps.fail("skin", fmt::format("{:g} m is more than 10 largest parcel diameters ({:g} m): the neighbour lists would "
                                "hold most pairs (0 = the default, 0.1 diameter)",
                                c.dem.skin, 10 * dmax));
}

// [domain], [physics] and [walls]: writes c.dem.domain (inside +-kMaxCoordinate, max > min),
// c.dem.periodic, c.dem.gravity and c.scene; reads c.species (walls.sdf_cutoff must reach
// the largest parcel radius).
void read_domain_and_walls(Config& cfg, const Section& root, const Section& ds, DemCase& c) {
  c.dem.domain = {ds.vec3("min"), ds.vec3("max")};
  for (int a = 0; a < 3; ++a) {
    if (!(std::fabs(c.dem.domain.lo[a]) <= kMaxCoordinate))
      ds.fail("min", fmt::format("every coordinate must lie in [-{0:g}, {0:g}] m", kMaxCoordinate));
    if (!(std::fabs(c.dem.domain.hi[a]) <= kMaxCoordinate))
      ds.fail("max", fmt::format("every coordinate must lie in [-{0:g}, {0:g}] m", kMaxCoordinate));
    if (!(c.dem.domain.hi[a] > c.dem.domain.lo[a])) ds.fail("max", "must exceed domain.min on every axis");
  }
  // Periodic axes, e.g. "y" for a slab: parcels leaving at one side come back at the other.
  const std::string periodic = ds.string_or("periodic", "none", {"none", "x", "y", "z", "xy", "xz", "yz", "xyz"});
  for (int a = 0; a < 3; ++a) c.dem.periodic[a] = periodic.find("xyz"[a]) != std::string::npos;
  c.dem.gravity = Section(&cfg, "physics").vec3_or("gravity", c.dem.gravity);
  for (int a = 0; a < 3; ++a)
    if (!(std::fabs(c.dem.gravity[a]) <= kMaxGravity))
      Section(&cfg, "physics").fail("gravity", fmt::format("every component must lie in [-{0:g}, {0:g}] m/s^2", kMaxGravity));
  c.scene = root.has("walls") ? geometry::read_scene(root.section("walls")) : geometry::Scene{};
  if (root.has("walls")) {
    Section ws = root.section("walls");
    double cutoff = ws.number_or("sdf_cutoff", 1e-3, Range::positive());
    double rmax = 0;
    for (const auto& s : c.species) rmax = std::max(rmax, 0.5 * s.diameter());
    if (cutoff < rmax) ws.fail("sdf_cutoff", fmt::format("must be at least the largest parcel radius {:g} m", rmax));
  }
}

// The neighbour search's cell grid over the domain (cells one interaction range wide, the
// largest diameter plus the skin): reads c, writes nothing; fails (on domain.max) when a
// periodic length is under three ranges or the grid has more than kMaxCells cells.
void check_search_grid(const Section& ds, const DemCase& c) {
  const double dmax = largest_diameter(c.species);
  const double range = dmax + (c.dem.skin > 0 ? c.dem.skin : 0.1 * dmax);
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= std::floor((c.dem.domain.hi[a] - c.dem.domain.lo[a]) / range) + 1;
  for (int a = 0; a < 3; ++a) {
    const double L = c.dem.domain.hi[a] - c.dem.domain.lo[a];
    if (c.dem.periodic[a] && L < 3 * range)
      ds.fail("max", fmt::format("periodic length {:.4g} m along axis {} is shorter than three interaction ranges "
                                 "(3 x {:.4g} m: largest diameter plus skin)",
                                 L, "xyz"[a], range));
  }
  if (!(cells <= kMaxCells))
    ds.fail("max", fmt::format("the domain spans {:.3g} neighbour-search cells of {:.4g} m (largest parcel diameter "
                               "plus skin), more than {:g}",
                               cells, range, kMaxCells));
}

// One [[particles.insert]]: its species, its region (a box inside the domain, or the die's
// cavity) and its size (count, or solid_volume rounded to parcels: at least one, at most
// kMaxParcels), no denser than kMaxPacking. Reads c.species and c.dem.domain.
InsertRegion read_insert(const Section& root, const Section& s, const DemCase& c) {
  InsertRegion r;
  r.species = species_index(c.species, s, "species");
  if (s.has("region")) {
    std::string where = s.string("region", {"die_filling_cavity"});
    if (!root.has("walls") || !root.section("walls").has("die_filling"))
      s.fail("region", "\"die_filling_cavity\" needs a [walls.die_filling] section");
    auto df = geometry::read_die_filling(root.section("walls").section("die_filling"));
    r.lo = df.cavity_lo();
    r.hi = df.cavity_hi();
  } else {
    r.lo = s.vec3("min");
    r.hi = s.vec3("max");
    for (int a = 0; a < 3; ++a) {
      if (!(r.hi[a] > r.lo[a])) s.fail("max", "must exceed min on every axis");
      if (r.lo[a] < c.dem.domain.lo[a] || r.hi[a] > c.dem.domain.hi[a])
        s.fail(r.lo[a] < c.dem.domain.lo[a] ? "min" : "max", "the region must lie inside the domain");
    }
  }
  const Species& sp = c.species[r.species];
  if (s.has("count") && s.has("solid_volume")) s.fail("count", "give either count or solid_volume, not both");
  const std::string count_key = s.has("solid_volume") ? "solid_volume" : "count";
  if (s.has("solid_volume")) {
    const double v = s.number("solid_volume", Range::positive());
    const double n = v / sp.volume();  // parcels
    if (!(n >= 0.5))
      s.fail("solid_volume", fmt::format("{:g} m^3 is less than half a parcel of species \"{}\" ({:.4g} m^3): it "
                                         "would insert no parcel",
                                         v, sp.name, sp.volume()));
    if (!(n <= static_cast<double>(kMaxParcels)))
      s.fail("solid_volume", fmt::format("{:g} m^3 is {:.4g} parcels of species \"{}\", more than {} per insert", v,
                                         n, sp.name, kMaxParcels));
    r.count = std::lround(n);
  } else {
    r.count = s.integer("count", Range::closed(1, static_cast<double>(kMaxParcels)));
  }
  const Vec3 box = r.hi - r.lo;
  const double fraction = r.count * sp.volume() / (box.x * box.y * box.z);
  if (!(fraction <= kMaxPacking))
    s.fail(count_key, fmt::format("{} parcels of {:.4g} m^3 would fill {:.3g} of the region's {:.4g} m^3; no packing "
                                  "of equal spheres exceeds {:.4f} (random insertion stops near 0.3)",
                                  r.count, sp.volume(), fraction, box.x * box.y * box.z, kMaxPacking));
  r.velocity = s.vec3_or("velocity", {0, 0, 0});
  return r;
}

// [time]: writes c.dem.dt, c.t_start, c.t_end (end after start, at most kMaxSteps steps);
// reads c.species and c.material: dt resolves the shortest collision time in at least
// time.min_steps_per_collision steps.
void read_time(const Section& ts, DemCase& c) {
  c.dem.dt = ts.number("dt", Range::open_closed(0, 1));
  c.t_start = ts.number_or("start", 0.0, Range::closed(-kMaxTime, kMaxTime));
  c.t_end = ts.number("end", Range::closed(-kMaxTime, kMaxTime));
  if (!(c.t_end > c.t_start)) ts.fail("end", fmt::format("must be later than time.start = {:g} s", c.t_start));
  if (!((c.t_end - c.t_start) / c.dem.dt <= kMaxSteps))
    ts.fail("dt", fmt::format("{:g} s makes {:.3g} steps from time.start to time.end, more than {:g}", c.dem.dt,
                              (c.t_end - c.t_start) / c.dem.dt, kMaxSteps));
  double steps_per_collision = ts.number_or("min_steps_per_collision", 10.0, Range::closed(2.0, 1e6));
  const double tc = contact::min_collision_time(c.species, c.material);
  if (c.dem.dt > tc / steps_per_collision)
    ts.fail("dt", fmt::format("{:g} s is too large: the shortest collision time is {:.4g} s and needs at least "
                              "time.min_steps_per_collision = {:g} steps (dt <= {:.4g} s)",
                              c.dem.dt, tc, steps_per_collision, tc / steps_per_collision));
}

// [output]: writes c.output.
void read_output(const Section& os, DemCase& c) {
  c.output.dir = os.string_or("dir", "out");
  c.output.energy_interval = os.number_or("energy_interval", 1e-3, Range::positive());
  c.output.snapshot_interval = os.number_or("snapshot_interval", 1e-2, Range::positive());
  c.output.progress_interval = os.number_or("progress_interval", 10.0, Range::positive());
  c.output.max_speed = os.number_or("max_speed", 50.0, Range::positive());
  c.output.checkpoint_interval = os.number_or("checkpoint_interval", 1e-2, Range::positive());
  c.output.tracer_time = os.number_or("tracer_time", 0.0, Range::any());
  c.output.compression = static_cast<int>(
      os.integer_or("compression", io::kDefaultCompression, Range::closed(0, io::kMaxCompression)));
  c.dem.accounts = os.boolean_or("energy_accounts", true);
}

}  // namespace

// The sections in the order their keys are read (the order of the key reference and of the
// first error a case gets): a later step reads what an earlier one wrote into c.
DemCase read_dem_case(Config& cfg) {
  DemCase c;
  Section root = cfg.root();
  Section ps = root.section("particles");
  read_species(ps, c);
  // [contact]: law (the registry, contact/laws.hpp) and that law's keys
  c.material = contact::read_contact_model(root.section("contact"));
  Section ds = root.section("domain");
  read_domain_and_walls(cfg, root, ds, c);
  check_search_grid(ds, c);
  // [[particles.insert]] and [[particles.file]]
  for (const Section& s : ps.sections("insert")) c.inserts.push_back(read_insert(root, s, c));
  for (const Section& s : ps.sections("file")) {
    ParticleFile f;
    f.path = s.string("path");
    f.species = species_index(c.species, s, "species");
    c.files.push_back(f);
  }
  if (c.inserts.empty() && c.files.empty())
    ps.fail("insert", "no particles: add [[particles.insert]] or [[particles.file]]");
  read_time(root.section("time"), c);
  read_output(root.section("output"), c);
  return c;
}

std::unique_ptr<DemSolver> build_solver(const DemCase& c, const std::string& case_dir) {
  auto dem = std::make_unique<DemSolver>(c.species, c.material, c.dem, c.scene);
  dem->set_time(c.t_start);
  geometry::Scene::Frame frame = dem->scene().at(c.t_start);
  for (const auto& f : c.files) {
    std::filesystem::path path(f.path);
    if (path.is_relative()) path = std::filesystem::path(case_dir) / path;
    std::string ext = path.extension().string();
    io::ParticleTable t = (ext == ".h5" || ext == ".hdf5") ? io::read_particles_h5(path.string())
                                                            : io::read_particles_csv(path.string());
    append_table(dem->particles(), c.species, t, f.species, path.string());
  }
  uint64_t seed = c.seed;
  for (const auto& r : c.inserts) {
    int64_t next_id = 0;
    for (auto id : dem->particles().id) next_id = std::max(next_id, id + 1);
    insert_random(dem->particles(), c.species, r, frame, seed++, next_id);
  }
  return dem;
}

}  // namespace cgdem::app
