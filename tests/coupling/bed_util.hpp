// A free bed of parcels on a floor with air blown in from below, for the fluidization
// and stability tests.
//
//   particles  periodic in x and y; a DEM floor (a HalfSpace wall body at z = 0, normal +z)
//              carries them. The floor's surface lies on the domain boundary, so the air's
//              immersed-boundary fractions are 0 in every cell (1/2 only on the boundary
//              z-faces, which are prescribed by the Wall side below and are not unknowns):
//              the floor blocks the parcels and not the air.
//   air        bottom side: a Wall with normal velocity U_w (prescribed inflow), top side:
//              Open (p = 0), periodic in x and y; gravity on (air hydrostatics included).
//              The inflow FLUX through a Wall face is E u = eps(bottom cell) U_w (the wall
//              velocity is an interstitial velocity): with the bed resting on the floor the
//              superficial velocity is eps_0 U_w, so it is measured (flux through the top,
//              where eps = 1) rather than assumed.
//   settling   the parcels start on a jittered lattice (solid fraction ~0.43) with small
//              random velocities and fall onto the floor in air at rest.
//
// The air's boundary velocity is a constructor parameter of FluidSolver; set_inflow replaces
// the solver object in place (the coupled solver holds a reference to it, the air state is
// kept), which is how a test raises U step by step.
#pragma once
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "coupled_util.hpp"

namespace cgdem::test {

struct BedSpec {
  double ratio = 3;           // l
  int nxy = 4, nz = 16;       // cells
  double dx = 0.6e-3;         // [m]
  int layers = 21;            // lattice layers of the initial state (nxy_p^2 parcels each)
  double spacing = 0.4e-3;    // lattice spacing of the initial state [m]
  double dt_dem = 1.2e-6;     // [s] (t_c = 1.23e-5 s: >= 10 steps per collision)
  double dt_fluid_max = 1e-4; // [s]
  double inflow = 0;          // U_w of the bottom Wall side [m/s]
  unsigned seed = 7;
  MaterialParams material{};  // k 50 N/m, e 0.9, mu 0.3 (paper, Table 1)
  DragCoupling coupling = DragCoupling::SemiImplicit;
};

struct Bed {
  BedSpec spec;
  fluid::FluidParams air_params;
  std::unique_ptr<CoupledSystem> sys;
  double area = 0;        // cross-section [m^2]
  double weight = 0;      // buoyant weight of the parcels [N] (at construction; parcels are never removed here)
};

inline fluid::FluidParams bed_air_params(const BedSpec& b, double inflow) {
  fluid::FluidParams a;
  a.rho = 1.0;
  a.mu = 1.8e-5;
  a.gravity = {0, 0, -9.81};
  a.bc = fluid::uniform_boundary(fluid::BcType::Periodic);
  a.bc[4] = {fluid::BcType::Wall, Vec3{0, 0, inflow}, 0};
  a.bc[5] = {fluid::BcType::Open, Vec3{}, 0};
  a.pressure.method = "pcg-fft";
  a.pressure.rel_tol = 1e-10;
  a.dt_max = 1e30;
  (void)b;
  return a;
}

// `start`: parcel positions and velocities to begin from (empty: the jittered lattice).
inline Bed make_bed(const BedSpec& b, const Particles* start = nullptr) {
  Bed bed;
  bed.spec = b;
  auto& sys = bed.sys;
  sys = std::make_unique<CoupledSystem>();
  const fluid::MacGrid g = make_grid(b.nxy, b.nxy, b.nz, b.dx);
  const Species sp{"powder", 125e-6, b.ratio, 1500};
  DemParams dp;
  dp.dt = b.dt_dem;
  dp.gravity = {0, 0, -9.81};
  dp.domain = {g.origin, g.origin + g.dx * Vec3{double(g.nx), double(g.ny), double(g.nz)}};
  dp.periodic = {true, true, false};
  geometry::Scene scene;
  const int floor = scene.add_body("floor", geometry::Motion{});
  scene.add_part(floor, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  sys->dem = std::make_unique<DemSolver>(std::vector<Species>{sp}, b.material, dp, scene);
  {
    Particles& p = sys->dem->particles();
    const double L = b.nxy * b.dx;
    const int n = static_cast<int>(std::floor(L / b.spacing + 1e-9));
    const double s = L / n;  // exact period of the lattice in x, y
    const double jitter = 0.45 * (s - sp.diameter());
    std::mt19937_64 rng(b.seed);
    std::uniform_real_distribution<double> u(-1, 1);
    int64_t id = 0;
    if (start)
      for (size_t i = 0; i < start->size(); ++i) p.add(id++, 0, sp, start->x[i], start->v[i], start->omega[i]);
    for (int k = 0; k < (start ? 0 : b.layers); ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec3 x{(i + 0.5) * s + jitter * u(rng), (j + 0.5) * s + jitter * u(rng),
                       0.5 * sp.diameter() + 2 * jitter + k * b.spacing + jitter * u(rng)};  // clear of the floor
          p.add(id++, 0, sp, x, 0.05 * Vec3{u(rng), u(rng), u(rng)});
        }
    bed.weight = p.size() * sp.mass() * 9.81 * (1 - 1.0 / sp.density);
    bed.area = L * L;
  }
  sys->air = fluid::make_fluid_state(g);
  bed.air_params = bed_air_params(b, b.inflow);
  sys->fluid = std::make_unique<fluid::FluidSolver>(g, bed.air_params);
  coupling::ExchangeParams ep;
  ep.air = {bed.air_params.rho, bed.air_params.mu};
  ep.bc = bed.air_params.bc;
  CoupledParams cp;
  cp.dt_fluid_max = b.dt_fluid_max;
  cp.coupling = b.coupling;
  sys->cs = std::make_unique<CoupledSolver>(*sys->dem, *sys->fluid, sys->air,
                                            coupling::Exchange(g, {sp}, ep), cp);
  return bed;
}

// New inflow velocity U_w of the bottom side (see the header comment).
inline void set_inflow(Bed& bed, double inflow) {
  bed.air_params = bed_air_params(bed.spec, inflow);
  *bed.sys->fluid = fluid::FluidSolver(bed.sys->air.grid, bed.air_params);
}

// U_w that makes the inflow flux eps_0 U_w equal to the superficial velocity U.
inline void set_superficial(Bed& bed, double U) {
  const auto& air = bed.sys->air;
  double e0 = 0;
  for (int j = 0; j < air.grid.ny; ++j)
    for (int i = 0; i < air.grid.nx; ++i) e0 += air.eps(i, j, 0) / (air.grid.nx * air.grid.ny);
  set_inflow(bed, U / e0);
}

struct BedState {
  double dp = 0;          // p(bottom cells) - p(top cells) - rho_f g dz [Pa]
  double superficial = 0; // mean E w through the top face [m/s]
  double z_mean = 0;      // centre of mass height [m]
  double z_top = 0;       // bed surface: mean height of the highest 10 % of parcels + d/2 [m]
  double ke = 0;          // translational kinetic energy per parcel [J]
  double v_max = 0;       // largest parcel speed [m/s]
  double eps_bulk = 0;    // 1 - solid volume / (A * 2 z_mean) (a uniform bed: height 2 z_mean)
  double eps_floor = 0;   // mean eps of the bottom cell layer
  double support = 0;     // sum over parcels of (drag + f_ext)_z minus the air's buoyancy [N]
  bool finite = true;
};

inline BedState measure(const Bed& bed) {
  const auto& air = bed.sys->air;
  const auto& g = air.grid;
  const Particles& p = bed.sys->dem->particles();
  BedState s;
  double p0 = 0, p1 = 0, flux = 0;
  const int kt = g.nz - 1;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      p0 += air.p(i, j, 0);
      p1 += air.p(i, j, kt);
      flux += air.eps(i, j, kt) * air.w(i, j, g.nz);
    }
  const double nc = g.nx * g.ny;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) s.eps_floor += air.eps(i, j, 0) / (g.nx * g.ny);
  s.dp = (p0 - p1) / nc - bed.air_params.rho * 9.81 * (kt * g.dx);
  s.superficial = flux / nc;
  std::vector<double> z(p.size());
  double vol = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    z[i] = p.x[i].z;
    s.z_mean += p.x[i].z / p.size();
    s.ke += 0.5 / p.inv_mass[i] * norm2(p.v[i]) / p.size();
    s.v_max = std::max(s.v_max, norm(p.v[i]));
    s.finite = s.finite && std::isfinite(p.x[i].z) && std::isfinite(p.v[i].z);
    const double V = 4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i];
    vol += V;
    s.support += p.drag[i] * (p.u_fluid[i].z - p.v[i].z) + p.f_ext[i].z - V * bed.air_params.rho * 9.81;
  }
  std::sort(z.begin(), z.end());
  const size_t top = std::max<size_t>(1, z.size() / 10);
  for (size_t i = z.size() - top; i < z.size(); ++i) s.z_top += z[i] / top;
  s.z_top += p.radius.empty() ? 0 : p.radius[0];
  s.eps_bulk = 1 - vol / (bed.area * 2 * s.z_mean);
  s.finite = s.finite && std::isfinite(s.dp);
  return s;
}

}  // namespace cgdem::test
