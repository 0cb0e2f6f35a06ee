#include "app/air_case.hpp"

#include <fmt/format.h>

#include <cmath>

#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::app {

namespace {

// Upper bounds of the [air] keys (also in air_case.hpp).
constexpr double kMaxCellsPerAxis = 1e5;
constexpr double kMaxCells = 1e8;  // ~10 GB of fields
constexpr double kMaxDensity = 1e4;     // kg/m^3
constexpr double kMaxViscosity = 1e2;   // Pa s

fluid::BcType side_type(const Section& s, const std::string& key, const std::string& def) {
  const std::string t = s.string_or(key, def, {"wall", "open", "periodic"});
  return t == "wall" ? fluid::BcType::Wall : (t == "open" ? fluid::BcType::Open : fluid::BcType::Periodic);
}

// The air grid: air.dx over the DEM domain, a whole number (>= 2) of cells along every axis,
// at most kMaxCellsPerAxis per axis and kMaxCells in all. Writes a.grid.
void read_grid(const Section& s, const DemParams& dem, AirCase& a) {
  const double dx = s.number_or("dx", 0.6e-3, Range::open_closed(0, 1));
  const Vec3 size = dem.domain.hi - dem.domain.lo;
  std::array<int, 3> n{};
  double cells = 1;
  for (int d = 0; d < 3; ++d) {
    const double nd = size[d] / dx;
    cells *= nd;
    if (!(nd <= kMaxCellsPerAxis) || !(cells <= kMaxCells))
      s.fail("dx", fmt::format("{:g} m makes {:.3g} cells along {} ({:.3g} in all so far); at most {:g} per axis and "
                               "{:g} in all",
                               dx, nd, "xyz"[d], cells, kMaxCellsPerAxis, kMaxCells));
    n[d] = static_cast<int>(std::lround(nd));
    if (n[d] < 2 || std::fabs(n[d] * dx - size[d]) > 1e-9 * size[d])
      s.fail("dx", fmt::format("the domain's {} extent {:g} m is not a whole number (>= 2) of cells of {:g} m",
                               "xyz"[d], size[d], dx));
  }
  a.grid.nx = n[0], a.grid.ny = n[1], a.grid.nz = n[2];
  a.grid.dx = dx;
  a.grid.origin = dem.domain.lo;
}

// The air's material and step, and the coupling's time step and scheme ([air.implicit] only
// with the implicit coupling; air.dt_max not under the DEM step). Writes a.fluid (without
// pressure and boundary) and a.coupled.
void read_air_and_coupling(const Section& s, const DemParams& dem, AirCase& a) {
  fluid::FluidParams& f = a.fluid;
  f.rho = s.number_or("density", 1.0, Range::open_closed(0, kMaxDensity));
  f.mu = s.number_or("viscosity", 1.8e-5, Range::open_closed(0, kMaxViscosity));
  f.gravity = dem.gravity;
  f.cfl = s.number_or("cfl", f.cfl, Range::open_closed(0, 1));
  f.time_order = static_cast<int>(s.integer_or("time_order", f.time_order, Range::closed(1, 2)));
  f.ibm_samples = static_cast<int>(s.integer_or("ibm_samples", f.ibm_samples, Range::closed(1, 16)));
  f.advection = fluid::Advection::VanLeer;

  a.coupled.dt_fluid_max = s.number_or("dt_max", 1e-4, Range::open_closed(0, 1));
  if (a.coupled.dt_fluid_max < dem.dt * (1 - 1e-12))
    s.fail("dt_max", fmt::format("{:g} s is shorter than the DEM step time.dt = {:g} s", a.coupled.dt_fluid_max, dem.dt));
  f.dt_max = a.coupled.dt_fluid_max;
  a.coupled.feedback = s.boolean_or("feedback", true);
  const std::string coupling = s.string_or("coupling", "semi-implicit", {"semi-implicit", "implicit"});
  a.coupled.coupling = coupling == "implicit" ? DragCoupling::Implicit : DragCoupling::SemiImplicit;
  if (auto is = s.optional_section("implicit")) {
    if (a.coupled.coupling != DragCoupling::Implicit)
      is->fail("method", "[air.implicit] is read only with air.coupling = \"implicit\"");
    ImplicitDragOptions& o = a.coupled.implicit;
    o.method = is->string_or("method", o.method, ImplicitDragOptions::methods());
    o.tol = is->number_or("tolerance", o.tol, Range::open_closed(0, 1));
    o.max_iterations = static_cast<int>(is->integer_or("max_iterations", o.max_iterations, Range::closed(1, 1000)));
    o.depth = static_cast<int>(is->integer_or("depth", o.depth, Range::closed(0, 20)));
  }
}

// [air.pressure]: the pressure solve (the method names from the registry,
// solvers/pressure/pressure_solver.hpp). Writes a.fluid.pressure, a.fluid.stage_rel_tol and
// a.mpi_preconditioner.
void read_pressure(const Section& ps, AirCase& a) {
  fluid::FluidParams& f = a.fluid;
  f.pressure.method = ps.string_or("method", "pcg-mgw3", pressure::pressure_method_names());
  f.pressure.krylov = ps.string_or("krylov", "sundials", {"sundials", "fused"});
  f.pressure.rel_tol = ps.number_or("tolerance", f.pressure.rel_tol, Range{0, 1, true, true});
  f.pressure.max_iter = static_cast<int>(ps.integer_or("max_iterations", f.pressure.max_iter, Range::closed(1, 1e6)));
  f.stage_rel_tol = ps.number_or("stage_tolerance", f.stage_rel_tol, Range{0, 1, true, true});
  a.mpi_preconditioner =
      ps.string_or("mpi_preconditioner", "auto", {"auto", "pfmg", "bj-mg", "bj-mg2", "bj-fft", "as-mg", "as-mg2", "none"});
}

// The still air's pressure on an open side: open_pressure is the pressure on the top plane
// (z_max; the plane the gravity points away from), and a side below it carries the weight of
// the air between them, rho g . (x_side - x_top), so that air at rest stays at rest between
// two open sides. An open side along which gravity has a component would need a pressure that
// varies over it (one value per side is what the pressure solve takes): refused.
double still_air_pressure(const Section& bs, const char* name, int side, double p_open, const DemParams& dem,
                          double rho) {
  const int axis = side / 2;
  const Vec3& g = dem.gravity;
  for (int b = 0; b < 3; ++b)
    if (b != axis && g[b] != 0)
      bs.fail(name, fmt::format("an open side must be normal to gravity ({}, {}, {}) m/s^2: the still air's pressure "
                                "would vary along it",
                                g.x, g.y, g.z));
  if (g[axis] == 0) return p_open;
  const double x_side = side % 2 == 0 ? dem.domain.lo[axis] : dem.domain.hi[axis];
  const double x_top = g[axis] < 0 ? dem.domain.hi[axis] : dem.domain.lo[axis];
  return p_open + rho * g[axis] * (x_side - x_top);
}

// [air.boundary]: the six sides (periodic exactly where the DEM domain is; by default walls
// and an open top), open sides at the still air's pressure. Writes a.fluid.bc.
void read_boundary(const Section& bs, const DemParams& dem, AirCase& a) {
  fluid::FluidParams& f = a.fluid;
  const char* names[6] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  const double p_open = bs.number_or("open_pressure", 0.0, Range::closed(-1e7, 1e7));
  for (int side = 0; side < 6; ++side) {
    const int axis = side / 2;
    const std::string def = dem.periodic[axis] ? "periodic" : (side == 5 ? "open" : "wall");
    f.bc[side].type = side_type(bs, names[side], def);
    f.bc[side].pressure =
        f.bc[side].type == fluid::BcType::Open ? still_air_pressure(bs, names[side], side, p_open, dem, f.rho) : p_open;
    if ((f.bc[side].type == fluid::BcType::Periodic) != dem.periodic[axis])
      bs.fail(names[side], fmt::format("must be \"periodic\" exactly when the {} axis is periodic in domain.periodic",
                                       "xyz"[axis]));
  }
}

// The momentum exchange with the parcels: drag law (the registry, coupling/drag.hpp), the
// air it sees, the void fraction's floor and next to walls. Reads a.fluid; writes a.exchange.
void read_exchange(const Section& s, AirCase& a) {
  const fluid::FluidParams& f = a.fluid;
  a.exchange.law = coupling::parse_drag_law(s.string_or("drag", "ergun-wen-yu", coupling::drag_law_names()));
  a.exchange.air = {f.rho, f.mu};
  a.exchange.eps_min = s.number_or("eps_min", 0.2, Range{0.0, 1.0, true, true});
  a.exchange.wall_porosity = s.string_or("wall_porosity", "packing", {"packing", "cell"}) == "cell"
                                 ? coupling::WallPorosity::Cell
                                 : coupling::WallPorosity::Packing;
  a.exchange.bc = f.bc;
}

}  // namespace

// The steps in the order their keys are read (the order of the key reference and of the first
// error a case gets); the parameters are validated as a whole at the end.
AirCase read_air_case(Config& cfg, const DemParams& dem) {
  AirCase a;
  Section root = cfg.root();
  if (!root.has("air")) return a;
  Section s = root.section("air");
  a.enabled = s.boolean_or("enabled", true);
  read_grid(s, dem, a);
  read_air_and_coupling(s, dem, a);
  read_pressure(s.optional_section("pressure").value_or(Section(&cfg, s.key_path("pressure"))), a);
  read_boundary(s.optional_section("boundary").value_or(Section(&cfg, s.key_path("boundary"))), dem, a);
  read_exchange(s, a);
  a.fluid.validate();
  return a;
}

}  // namespace cgdem::app
