// The parcel <-> air exchange on blocks over MPI ranks (coupling::Exchange with
// air_mpi::HaloSync) against the exchange on the whole grid in one process: the void
// fraction, the air at the parcels (u_f, drag coefficient, pressure force) and the drag
// deposits K, K v. 600 parcels scattered over the whole grid, many within a kernel width
// of the cuts (the TSC kernel then reaches into the neighbour's cells), a wall body on the
// floor (masked weights next to it, across the cuts), Wall sides and an Open top.
// Each rank holds the parcels whose centres lie in its cells. The deposits of one parcel
// are the same numbers on both sides; only the order of the sums differs where a cell gets
// parcels of two blocks, and the blocks' grids have their own origins (positions relative to
// the nodes differ in the last bit), so the fields and the per-parcel values must agree to
// 1e-13 of their largest magnitudes (measured: 1e-16 .. 1e-15).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "parallel/mpi/field_gather.hpp"
#include "parallel/mpi/halo_sync.hpp"
#include "coupling/exchange.hpp"
#include "mpi_air_util.hpp"

namespace cgdem::air_mpi {
namespace {

const std::array<int, 3> kN{16, 12, 10};
constexpr double kDx = 1e-3;

fluid::MacGrid whole_grid() { return fluid::MacGrid{kN[0], kN[1], kN[2], kDx, {-2e-3, 0.0, 1e-3}}; }

fluid::FluidBoundary boundary() {
  fluid::FluidBoundary bc = fluid::uniform_boundary(fluid::BcType::Wall);
  bc[5].type = fluid::BcType::Open;
  bc[5].pressure = 2.0;
  return bc;
}

// The parcels of the whole grid, the same on every rank (fixed seed).
Particles all_parcels(const Species& sp) {
  const fluid::MacGrid g = whole_grid();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  Particles p;
  for (int id = 0; id < 600; ++id) {
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = g.origin[a] + (0.3 + (g.n()[a] - 0.6) * u(rng)) * g.dx;
    p.add(id, 0, sp, x, Vec3{0.1 * u(rng), -0.05 * u(rng), 0.2 * (u(rng) - 0.5)});
  }
  return p;
}

geometry::Scene scene() {
  geometry::Scene s;
  const fluid::MacGrid g = whole_grid();
  const int b = s.add_body("step", geometry::Motion::constant({0, 0, 0}));
  s.add_part(b, "step", geometry::make_box(g.origin + Vec3{-1e-3, -1e-3, -1e-3}, g.origin + Vec3{9.4e-3, 7.7e-3, 2.6e-3}));
  return s;
}

// Air fields as functions of position: the same on the whole grid and on any block.
void set_air(fluid::FluidState& a) {
  const fluid::MacGrid& g = a.grid;
  for (int d = 0; d < 3; ++d) {
    fluid::Field& f = a.vel(d);
    const auto e = f.extent();
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          const Vec3 x = g.face_centre(d, i, j, k);
          f(i, j, k) = 0.3 * std::sin(700 * x.x + 200 * d) * std::cos(500 * x.y) + 0.1 * std::sin(300 * x.z);
        }
  }
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) a.p(i, j, k) = 5 * std::cos(400 * g.cell_centre(i, j, k).x) + 300 * g.cell_centre(i, j, k).z;
}

struct Outcome {
  fluid::Field eps;
  std::array<fluid::Field, 3> K, Kv;
  std::map<int64_t, std::array<double, 7>> at_parcel;  // u_f, drag, f_ext by id
};

// The exchange of the parcels `p` on grid g; sync null: the whole grid, serially.
Outcome exchange(const fluid::MacGrid& g, const fluid::FluidBoundary& bc, const Species& sp, Particles p,
                 fluid::FieldSync* sync) {
  coupling::ExchangeParams xp;
  xp.bc = bc;
  xp.air = {1.2, 1.8e-5};
  coupling::Exchange ex(g, {sp}, xp);
  ex.set_sync(sync);
  fluid::IbmFractions walls;
  const geometry::Scene sc = scene();
  fluid::update_ibm(g, sc.at(0), 4, walls);
  if (sync) {
    sync->copy_ghosts(walls.alpha_cell, fluid::kCells);
    for (int d = 0; d < 3; ++d) sync->copy_ghosts(walls.alpha_face[d], d);
    walls.any_solid = sync->any(walls.any_solid);  // as CoupledSolver::walls_at does
  }
  ex.set_walls(&walls);
  coupling::ParcelWeights w;
  ex.weights(p, p.size(), w);
  fluid::FluidState air = fluid::make_fluid_state(g);
  Outcome o;
  ex.void_fraction(p, w, air.eps);
  o.eps = air.eps;
  set_air(air);
  fluid::SerialSync serial(g, bc);
  fluid::FieldSync& s = sync ? *sync : static_cast<fluid::FieldSync&>(serial);
  s.fill_velocity(air.u, air.v, air.w);
  s.fill_scalar(air.p, fluid::ScalarKind::Pressure);
  ex.air_to_parcels(air, w, p);
  for (size_t i = 0; i < p.size(); ++i) {
    p.j_drag[i] = 1e-4 * p.drag[i] * (p.u_fluid[i] - p.v[i]);
    o.at_parcel[p.id[i]] = {p.u_fluid[i].x, p.u_fluid[i].y, p.u_fluid[i].z, p.drag[i],
                            p.f_ext[i].x,   p.f_ext[i].y,   p.f_ext[i].z};
  }
  fluid::Sources src;
  ex.parcels_to_air(p, w, 1e-4, src);
  o.K = src.K, o.Kv = src.Kv;
  return o;
}

double max_abs(const fluid::Field& f) {
  double m = 0;
  const auto e = f.extent();
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i) m = std::max(m, std::fabs(f(i, j, k)));
  return m;
}

double max_diff(const fluid::Field& a, const fluid::Field& b) {
  double m = 0;
  const auto e = a.extent();
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i) m = std::max(m, std::fabs(a(i, j, k) - b(i, j, k)));
  return m;
}

TEST(ExchangeMpi, BlocksMatchTheWholeGrid) {
  Species sp;
  sp.name = "powder";
  sp.d_original = 125e-6;
  sp.ratio = 3;
  sp.density = 1500;
  const fluid::MacGrid whole = whole_grid();
  const fluid::FluidBoundary bc = boundary();
  const Particles everyone = all_parcels(sp);
  const Outcome serial = exchange(whole, bc, sp, everyone, nullptr);
  double worst_field = 0, worst_parcel = 0;
  long parcels_seen = 0;
  for (const GridBlocks& b : test::layouts(kN)) {
    HaloSync sync(MPI_COMM_WORLD, b, whole, bc);
    const fluid::MacGrid& g = sync.local_grid();
    Particles mine;
    std::vector<int> keep;
    for (size_t i = 0; i < everyone.size(); ++i) {
      bool in = true;
      for (int a = 0; a < 3; ++a) {
        const double lo = whole.origin[a] + b.lo()[a] * kDx, hi = whole.origin[a] + b.hi()[a] * kDx;
        in = in && everyone.x[i][a] >= lo && everyone.x[i][a] < hi;
      }
      if (in) keep.push_back(static_cast<int>(i));
    }
    mine = everyone;
    mine.reorder(keep);
    const Outcome dist = exchange(g, sync.local_bc(), sp, mine, &sync);
    // Fields gathered on rank 0.
    std::vector<std::pair<const char*, double>> errs;
    const fluid::Field eps = gather_field(MPI_COMM_WORLD, b, dist.eps, kCellCentred);
    double eK = 0, eKv = 0;
    std::array<fluid::Field, 3> K, Kv;
    for (int d = 0; d < 3; ++d) {
      K[d] = gather_field(MPI_COMM_WORLD, b, dist.K[d], d);
      Kv[d] = gather_field(MPI_COMM_WORLD, b, dist.Kv[d], d);
    }
    double ep = 0, scale[7] = {0, 0, 0, 0, 0, 0, 0};  // per quantity: its largest magnitude
    for (const auto& [id, v] : serial.at_parcel)
      for (int q = 0; q < 7; ++q) scale[q] = std::max(scale[q], std::fabs(v[q]));
    for (const auto& [id, v] : dist.at_parcel) {
      const auto& s = serial.at_parcel.at(id);
      for (int q = 0; q < 7; ++q) ep = std::max(ep, std::fabs(v[q] - s[q]) / scale[q]);
    }
    ep = test::maxed(ep);
    const long seen = test::summed(static_cast<long>(dist.at_parcel.size()));
    if (b.rank() == 0) {
      double e_eps = max_diff(eps, serial.eps);
      for (int d = 0; d < 3; ++d) {
        eK = std::max(eK, max_diff(K[d], serial.K[d]) / max_abs(serial.K[d]));
        eKv = std::max(eKv, max_diff(Kv[d], serial.Kv[d]) / max_abs(serial.Kv[d]));
      }
      std::printf("[ error ] %d rank(s), blocks %d x %d x %d: max |eps - eps_serial| = %.2e (tol 1e-13); K %.2e, "
                  "K v %.2e of their largest value (tol 1e-13); at the parcels (u_f, drag, f_ext) %.2e of their "
                  "largest values (tol 1e-13); %ld of %zu parcels\n",
                  test::world_size(), b.dims()[0], b.dims()[1], b.dims()[2], e_eps, eK, eKv, ep, seen,
                  everyone.size());
      worst_field = std::max({worst_field, e_eps, eK, eKv});
    }
    worst_parcel = std::max(worst_parcel, ep);
    parcels_seen = seen;
  }
  worst_field = test::maxed(worst_field);
  EXPECT_LT(worst_field, 1e-13);
  EXPECT_LT(worst_parcel, 1e-13);
  EXPECT_EQ(parcels_seen, 600);
}

}  // namespace
}  // namespace cgdem::air_mpi
