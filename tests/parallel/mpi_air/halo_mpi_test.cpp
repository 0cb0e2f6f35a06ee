// Halo exchange of the air fields over MPI (issue 6, item 2): cell fields and the three face
// fields, on the cuts of mpi_air_util.hpp.
//   * exchange: every ghost inside the domain equals the global analytic value (bitwise),
//     physical-side ghosts are left alone;
//   * with the boundary fills: every entry equals that of a serial fill of the global grid
//     (bitwise), including the edges and corners where cuts meet physical sides;
//   * reverse_add: deposits reaching into ghosts end up where a serial deposit puts them
//     (bitwise: the weights are dyadic, so every sum is exact in any order), totals equal.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <limits>

#include "../../error_of.hpp"
#include "parallel/mpi/halo.hpp"
#include "mpi_air_util.hpp"

namespace cgdem::air_mpi {
namespace {

using fluid::Field;
using fluid::kGhost;
using test::summed;
using test::world_rank;

const std::array<int, 3> kCells{12, 10, 7};
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// The global analytic field of component `stagger` (-1: cell centred) at a global index.
double value(int stagger, int i, int j, int k) {
  return 100.0 * (stagger + 2) + i + 0.01 * j + 1e-4 * k + std::sin(0.37 * i + 0.11 * j + 0.05 * k);
}

std::array<int, 3> extent_of(const GridBlocks& b, int stagger) {
  auto e = b.local_cells();
  if (stagger >= 0) e[stagger] += 1;
  return e;
}

// Local entries this block owns along axis a: cells [0, n), faces [0, n) on an upper cut,
// [0, n] on an upper physical side.
bool owned_along(const GridBlocks& b, int stagger, int a, int l) {
  const int n = b.local_cells()[a];
  const int top = n + (stagger == a && !b.is_cut(2 * a + 1) ? 1 : 0);
  return l >= 0 && l < top;
}

// Visits every padded entry of a local field with its global index.
template <class Fn>
void for_all(const GridBlocks& b, Field& f, Fn fn) {
  const auto e = f.extent();
  for (int k = -kGhost; k < e[2] + kGhost; ++k)
    for (int j = -kGhost; j < e[1] + kGhost; ++j)
      for (int i = -kGhost; i < e[0] + kGhost; ++i)
        fn(std::array<int, 3>{i, j, k}, std::array<int, 3>{b.lo()[0] + i, b.lo()[1] + j, b.lo()[2] + k}, f(i, j, k));
}

std::string layout_name(const GridBlocks& b) { return fmt::format("{}x{}x{}", b.dims()[0], b.dims()[1], b.dims()[2]); }

TEST(AirHalo, GhostsInsideTheDomainGetTheNeighboursValues) {
  for (const GridBlocks& b : test::layouts(kCells)) {
    Halo halo(MPI_COMM_WORLD, b);
    for (int st = -1; st < 3; ++st) {
      Field f(extent_of(b, st), kNaN);
      for_all(b, f, [&](auto l, auto g, double& v) {
        if (owned_along(b, st, 0, l[0]) && owned_along(b, st, 1, l[1]) && owned_along(b, st, 2, l[2]))
          v = value(st, g[0], g[1], g[2]);
      });
      halo.exchange(f, st);
      long bad = 0, filled = 0;
      for_all(b, f, [&](auto l, auto g, double& v) {
        bool inside = true, owned = true;
        for (int a = 0; a < 3; ++a) {
          const int n = kCells[a] + (st == a ? 1 : 0);
          inside = inside && g[a] >= 0 && g[a] < n;
          owned = owned && owned_along(b, st, a, l[a]);
        }
        if (inside) {
          const double want = value(st, g[0], g[1], g[2]);
          if (std::memcmp(&v, &want, sizeof v) != 0) ++bad;
          if (!owned) ++filled;
        } else if (!std::isnan(v)) {
          ++bad;  // a physical-side ghost: not the exchange's business
        }
      });
      bad = summed(bad), filled = summed(filled);
      if (world_rank() == 0)
        std::printf("[ halo     ] %s stagger %2d: %ld ghosts filled from neighbours, %ld wrong\n",
                    layout_name(b).c_str(), st, filled, bad);
      EXPECT_EQ(bad, 0) << layout_name(b) << " stagger " << st;
      if (b.ranks() > 1) {
        EXPECT_GT(filled, 0);
      }
    }
  }
}

// A mixed boundary with moving walls and open sides of non-zero pressure.
fluid::FluidBoundary mixed_boundary() {
  using fluid::BcType;
  fluid::FluidBoundary bc;
  bc[0] = {BcType::Wall, {0.1, -0.2, 0.3}, 0};
  bc[1] = {BcType::Open, {}, 5.0};
  bc[2] = {BcType::Wall, {0.4, 0.0, 0.2}, 0};
  bc[3] = {BcType::Wall, {}, 0};
  bc[4] = {BcType::Wall, {-0.3, 0.1, 0.0}, 0};
  bc[5] = {BcType::Open, {}, -3.0};
  return bc;
}

TEST(AirHalo, FillsAndExchangeEqualASerialFill) {
  fluid::MacGrid global;
  global.nx = kCells[0], global.ny = kCells[1], global.nz = kCells[2];
  global.dx = 6e-4;
  const fluid::FluidBoundary bc = mixed_boundary();
  // The serial reference on the global grid.
  Field ref[4];
  for (int st = -1; st < 3; ++st) {
    Field& r = ref[st + 1];
    r = st < 0 ? fluid::make_cell_field(global) : fluid::make_face_field(global, st);
    const auto e = r.extent();
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) r(i, j, k) = value(st, i, j, k);
  }
  Field ref_p = ref[0];
  fluid::fill_scalar_ghosts(global, bc, ref[0], fluid::ScalarKind::ZeroGradient);
  fluid::fill_scalar_ghosts(global, bc, ref_p, fluid::ScalarKind::Pressure);
  fluid::fill_velocity_ghosts(global, bc, ref[1], ref[2], ref[3]);

  for (const GridBlocks& b : test::layouts(kCells)) {
    Halo halo(MPI_COMM_WORLD, b);
    const fluid::MacGrid local = b.local_grid(global);
    Field f[4], p;
    for (int st = -1; st < 3; ++st) {
      f[st + 1] = Field(extent_of(b, st), kNaN);
      for_all(b, f[st + 1], [&](auto l, auto g, double& v) {
        if (owned_along(b, st, 0, l[0]) && owned_along(b, st, 1, l[1]) && owned_along(b, st, 2, l[2]))
          v = value(st, g[0], g[1], g[2]);
      });
    }
    p = f[0];
    fill_scalar(halo, local, bc, f[0], fluid::ScalarKind::ZeroGradient);
    fill_scalar(halo, local, bc, p, fluid::ScalarKind::Pressure);
    fill_velocity(halo, local, bc, f[1], f[2], f[3]);
    auto compare = [&](Field& mine, const Field& want, const char* what) {
      long bad = 0;
      for_all(b, mine, [&](auto, auto g, double& v) {
        const double w = want(g[0], g[1], g[2]);
        if (std::memcmp(&v, &w, sizeof v) != 0) ++bad;
      });
      bad = summed(bad);
      EXPECT_EQ(bad, 0) << layout_name(b) << " " << what;
      if (world_rank() == 0) std::printf("[ fill     ] %s %-13s: %ld entries differ from the serial fill\n",
                                         layout_name(b).c_str(), what, bad);
    };
    compare(f[0], ref[0], "zero gradient");
    compare(p, ref_p, "pressure");
    compare(f[1], ref[1], "u");
    compare(f[2], ref[2], "v");
    compare(f[3], ref[3], "w");
  }
}

// A deterministic stream of deposits: cell, mass 1..8, and a face offset per axis.
struct Deposit {
  std::array<int, 3> cell;
  std::array<int, 3> up;  // the face of axis d is cell[d] + up[d]
  double mass;
};
std::vector<Deposit> deposits(int count) {
  std::vector<Deposit> out;
  uint64_t s = 88172645463325252ull;
  auto next = [&s] {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return s;
  };
  for (int q = 0; q < count; ++q) {
    Deposit d;
    for (int a = 0; a < 3; ++a) d.cell[a] = int(next() % kCells[a]), d.up[a] = int(next() % 2);
    d.mass = double(1 + next() % 8);
    out.push_back(d);
  }
  return out;
}

// Adds a 3 x 3 x 3 stencil of dyadic weights (1/4, 1/2, 1/4 per axis) around the deposit's
// cell, or around its face along `stagger`; `shift` turns global into field indices.
void deposit(Field& f, const Deposit& d, int stagger, const std::array<int, 3>& shift) {
  static const double w[3] = {0.25, 0.5, 0.25};
  std::array<int, 3> c = d.cell;
  if (stagger >= 0) c[stagger] += d.up[stagger];
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
        f(c[0] + di - shift[0], c[1] + dj - shift[1], c[2] + dk - shift[2]) += d.mass * w[di + 1] * w[dj + 1] * w[dk + 1];
}

TEST(AirHalo, ReverseAddGivesTheSerialDeposit) {
  const std::vector<Deposit> all = deposits(600);
  for (const GridBlocks& b : test::layouts(kCells)) {
    Halo halo(MPI_COMM_WORLD, b);
    for (int st = -1; st < 3; ++st) {
      std::array<int, 3> ge = kCells;
      if (st >= 0) ge[st] += 1;
      Field ref(ge, 0.0), f(extent_of(b, st), 0.0);
      for (const Deposit& d : all) {
        deposit(ref, d, st, {0, 0, 0});
        bool mine = true;
        for (int a = 0; a < 3; ++a) mine = mine && d.cell[a] >= b.lo()[a] && d.cell[a] < b.hi()[a];
        if (mine) deposit(f, d, st, b.lo());
      }
      halo.reverse_add(f, st);
      long bad = 0, reached = 0;
      double total = 0;
      for_all(b, f, [&](auto l, auto g, double& v) {
        bool cut_ghost = false;
        for (int a = 0; a < 3; ++a) {
          const int n = b.local_cells()[a];
          cut_ghost = cut_ghost || (l[a] < 0 && b.is_cut(2 * a)) ||
                      (l[a] >= n + (st == a && !b.is_cut(2 * a + 1) ? 1 : 0) && b.is_cut(2 * a + 1));
        }
        if (cut_ghost) {
          if (v != 0.0) ++bad;
          return;
        }
        total += v;
        const double w = ref(g[0], g[1], g[2]);
        if (std::memcmp(&v, &w, sizeof v) != 0) ++bad;
      });
      // Deposits of this rank that reached into a cut ghost (so the test exercises the exchange).
      for (const Deposit& d : all) {
        bool mine = true, near = false;
        for (int a = 0; a < 3; ++a) {
          mine = mine && d.cell[a] >= b.lo()[a] && d.cell[a] < b.hi()[a];
          const int c = d.cell[a] + (st == a ? d.up[a] : 0);
          near = near || (c - 1 < b.lo()[a] && b.is_cut(2 * a)) || (c + 1 >= b.hi()[a] && b.is_cut(2 * a + 1));
        }
        if (mine && near) ++reached;
      }
      double ref_total = 0;
      for (long q = 0; q < long(ge[0] + 2 * kGhost) * (ge[1] + 2 * kGhost) * (ge[2] + 2 * kGhost); ++q)
        ref_total += ref.data()[q];
      MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      bad = summed(bad), reached = summed(reached);
      if (world_rank() == 0)
        std::printf("[ deposit  ] %s stagger %2d: %ld deposits cross a cut, total %.17g (serial %.17g), %ld wrong\n",
                    layout_name(b).c_str(), st, reached, total, ref_total, bad);
      EXPECT_EQ(bad, 0) << layout_name(b) << " stagger " << st;
      EXPECT_EQ(total, ref_total);
      if (b.ranks() > 1) {
        EXPECT_GT(reached, 0);
      }
    }
  }
}

TEST(AirHalo, BadInputIsRefused) {
  const GridBlocks b = test::layouts(kCells).front();
  Halo halo(MPI_COMM_WORLD, b);
  Field wrong(3, 3, 3);
  EXPECT_NE(cgdem::test::error_of([&] { halo.exchange(wrong, kCellCentred); }).find("expected"), std::string::npos);
  EXPECT_NE(cgdem::test::error_of([] { GridBlocks({8, 8, 8}, Dims{4, 1, 1}, 0); }).find("kGhost + 1"),
            std::string::npos);
  fluid::FluidBoundary per = fluid::uniform_boundary(fluid::BcType::Periodic);
  EXPECT_NE(cgdem::test::error_of([&] { local_boundary(b, per); }).find("periodic"), std::string::npos);
}

}  // namespace
}  // namespace cgdem::air_mpi

namespace cgdem::air_mpi {
namespace {

// The die-filling grid gets the dims of docs/scale_out.md (those of parallel::choose_dims).
TEST(AirBlocks, DimsOfTheDieFillingGrid) {
  const std::array<int, 3> die{140, 70, 50};
  EXPECT_EQ(choose_block_dims(1, die), (Dims{1, 1, 1}));
  EXPECT_EQ(choose_block_dims(2, die), (Dims{2, 1, 1}));
  EXPECT_EQ(choose_block_dims(4, die), (Dims{4, 1, 1}));
  EXPECT_EQ(choose_block_dims(16, die), (Dims{4, 2, 2}));
  EXPECT_EQ(choose_block_dims(64, die), (Dims{8, 4, 2}));
  EXPECT_EQ(choose_block_dims(256, die), (Dims{16, 4, 4}));
  // Runs differ by at most one cell and tile the axis.
  const GridBlocks b(std::array<int, 3>{10, 7, 5}, Dims{3, 2, 1}, 5);
  EXPECT_EQ(b.coords(), (Dims{2, 1, 0}));
  EXPECT_EQ(b.lo(), (std::array<int, 3>{6, 3, 0}));
  EXPECT_EQ(b.hi(), (std::array<int, 3>{10, 7, 5}));
  EXPECT_EQ(b.neighbour(0), 4);
  EXPECT_EQ(b.neighbour(1), -1);
  EXPECT_EQ(b.neighbour(2), 2);
  EXPECT_EQ(b.neighbour(3), -1);
}

}  // namespace
}  // namespace cgdem::air_mpi
