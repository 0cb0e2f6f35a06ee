// A small coupled system for the verification tests: DEM + air on a box, walls inside optional.
#pragma once
#include <cmath>
#include <cstdio>
#include <memory>

#include "solvers/coupled/coupled_solver.hpp"

namespace cgdem::test {

struct CoupledSystem {
  std::unique_ptr<DemSolver> dem;
  fluid::FluidState air;
  std::unique_ptr<fluid::FluidSolver> fluid;
  std::unique_ptr<CoupledSolver> cs;
};

struct SystemSpec {
  fluid::MacGrid grid;
  fluid::FluidParams air;          // rho, mu, gravity, bc, pressure options
  std::vector<Species> species;
  MaterialParams material;
  DemParams dem;                   // dt, gravity (domain and periodic axes are set here)
  CoupledParams coupled;
  double eps_min = 0.2;
  geometry::Scene scene;           // walls inside the box (none by default)
  coupling::WallPorosity wall_porosity = coupling::WallPorosity::Packing;
};

inline fluid::MacGrid make_grid(int nx, int ny, int nz, double dx) {
  fluid::MacGrid g;
  g.nx = nx, g.ny = ny, g.nz = nz, g.dx = dx;
  return g;
}

// Builds the system; `add` fills the particles before the coupling maps eps.
template <class AddParticles>
std::unique_ptr<CoupledSystem> make_system(SystemSpec s, AddParticles add) {
  auto sys = std::make_unique<CoupledSystem>();
  const auto& g = s.grid;
  s.dem.domain = {g.origin, g.origin + g.dx * Vec3{double(g.nx), double(g.ny), double(g.nz)}};
  for (int a = 0; a < 3; ++a) s.dem.periodic[a] = s.air.bc[2 * a].type == fluid::BcType::Periodic;
  sys->dem = std::make_unique<DemSolver>(s.species, s.material, s.dem, s.scene);
  add(sys->dem->particles());
  sys->air = fluid::make_fluid_state(g);
  sys->fluid = std::make_unique<fluid::FluidSolver>(g, s.air);
  coupling::ExchangeParams ep;
  ep.air = {s.air.rho, s.air.mu};
  ep.bc = s.air.bc;
  ep.eps_min = s.eps_min;
  ep.wall_porosity = s.wall_porosity;
  sys->cs = std::make_unique<CoupledSolver>(*sys->dem, *sys->fluid, sys->air,
                                            coupling::Exchange(g, s.species, ep), s.coupled);
  return sys;
}

// A simple cubic lattice of parcels of species 0: n_xy x n_xy x n_z sites of spacing a,
// the first layer's centres at z0 + a/2 (a fixed bed when the coupling holds them in place).
inline void add_cubic_lattice(Particles& p, const Species& sp, int n_xy, int n_z, double a, double z0) {
  int64_t id = static_cast<int64_t>(p.size());
  for (int k = 0; k < n_z; ++k)
    for (int j = 0; j < n_xy; ++j)
      for (int i = 0; i < n_xy; ++i) p.add(id++, 0, sp, {(i + 0.5) * a, (j + 0.5) * a, z0 + (k + 0.5) * a});
}

inline double rel_err(double got, double want) { return std::fabs(got - want) / std::fabs(want); }

}  // namespace cgdem::test
