#include "solvers/run_mpi/mpi_domain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "parallel/mpi/field_gather.hpp"
#include "solvers/fluid/fluid_solver.hpp"
#include "solvers/pressure_mpi/dist_pressure.hpp"
#include "solvers/pressure_mpi/pfmg.hpp"

namespace cgdem::run {

namespace {

// Cuts of the parcels' blocks moved onto the nearest cell faces of the air grid, so that
// each rank's parcels and air cells are one block: no run shorter than kGhost + 1 cells.
// Returns the run starts of every axis (cells) and rewrites the cuts to match.
air_mpi::GridBlocks::Starts snap_to_cells(parallel::Decomposition::Cuts& cuts, const fluid::MacGrid& g) {
  air_mpi::GridBlocks::Starts starts;
  const int min_run = fluid::kGhost + 1;
  for (int a = 0; a < 3; ++a) {
    const int n = g.n()[a], p = static_cast<int>(cuts[a].size()) - 1;
    if (p > 1 && n < p * min_run)
      throw ConfigError(fmt::format("the air grid has {} cells along {}, too few for {} blocks of at least {} cells",
                                    n, "xyz"[a], p, min_run));
    starts[a] = {0};
    for (int m = 1; m < p; ++m) {
      int c = static_cast<int>(std::lround((cuts[a][m] - g.origin[a]) / g.dx));
      c = std::clamp(c, starts[a].back() + min_run, n - (p - m) * min_run);
      starts[a].push_back(c);
      cuts[a][m] = g.origin[a] + g.dx * c;
    }
    starts[a].push_back(n);
  }
  return starts;
}

// The block's entries of a field of the whole grid (interior entries, the cut faces included).
void copy_block(const air_mpi::GridBlocks& b, const fluid::Field& whole, fluid::Field& local) {
  const auto e = local.extent();
  const auto lo = b.lo();
  for (int k = 0; k < e[2]; ++k)
    for (int j = 0; j < e[1]; ++j)
      for (int i = 0; i < e[0]; ++i) local(i, j, k) = whole(i + lo[0], j + lo[1], k + lo[2]);
}

// What a run with air cannot do over ranks.
void refuse_over_ranks(const DemSolver& dem, const AirSpec& air) {
  if (air.coupled.coupling == DragCoupling::Implicit)
    throw ConfigError("air.coupling = \"implicit\" runs on one process only: the implicit drag coupling over MPI "
                      "ranks is not implemented (run without mpirun, or with air.coupling = \"semi-implicit\")");
  for (int a = 0; a < 3; ++a)
    if (dem.params().periodic[a])
      throw ConfigError(
          fmt::format("periodic axes are not supported over MPI ranks (the {} axis is periodic)", "xyz"[a]));
}

}  // namespace

MpiDomain::MpiDomain(MPI_Comm comm) : comm_(comm) {}
MpiDomain::~MpiDomain() = default;

// Blocks that share the parcels out evenly (every rank holds all of them here): the block
// counts from the parcels' extent (the least cut area through them), the cuts at the
// quantiles of their positions, no block narrower than one interaction range; with air, a
// cell more (moving a cut onto a cell face may narrow a block by dx/2).
void MpiDomain::decompose(const DemSolver& dem, const std::vector<Vec3>& where, const AirSpec* air) {
  with_air_ = air != nullptr;
  if (air) refuse_over_ranks(dem, *air), grid_ = air->grid;
  const geometry::Aabb& box = dem.params().domain;
  double r_max = 0;
  for (const auto& s : dem.species()) r_max = std::max(r_max, 0.5 * s.diameter());
  const double range = 2 * r_max + dem.params().skin;
  Vec3 lo = box.hi, hi = box.lo;
  for (const Vec3& x : where) lo = cmin(lo, x), hi = cmax(hi, x);
  Vec3 extent;
  for (int a = 0; a < 3; ++a) extent[a] = std::max(hi[a] - lo[a], 0.0) + range;
  parallel::Decomposition::Cuts cuts;
  for (int a = 0; a < 3; ++a) cuts[a] = {box.lo[a], box.hi[a]};
  comm_.together("decomposition", false, [&] {
    if (comm_.size() > 1)
      cuts = parallel::balanced_cuts(box, parallel::choose_dims(comm_.size(), extent), where,
                                     air ? range + grid_.dx : range);
    if (!air) return;
    starts_ = snap_to_cells(cuts, grid_);
    if (comm_.size() > 1 && !(dem.params().skin < grid_.dx))
      throw ConfigError(fmt::format(
          "over MPI ranks a parcel may stray half the neighbour-list skin ({:g} m) beyond its block between list "
          "builds, and its coupling kernel must stay within the {} ghost layers of air cells: the skin must be "
          "shorter than the cell size air.dx = {:g} m",
          dem.params().skin, fluid::kGhost, grid_.dx));
  });
  d_.emplace(box, cuts);
}

std::unique_ptr<DomainExchange> MpiDomain::attach(DemSolver& dem) {
  std::unique_ptr<parallel::DistributedDem> x;
  comm_.together("decomposition", false,
                 [&] { x = std::make_unique<parallel::DistributedDem>(comm_.comm(), *d_, dem); });
  dist_ = x.get();
  return x;
}

// The air of this rank's block: grid, boundary (cut sides marked), the distributed
// pressure solve, the coupling's exchanges, all through one HaloSync.
AirShare MpiDomain::share_air(const AirSpec& air) {
  std::string preconditioner = air.mpi_preconditioner;
  // "auto": additive Schwarz multigrid on a few ranks (4 ms of Case 1-3 on 2 ranks: 30.9 PCG
  // iterations and 5.4 s of solves per 20 fluid steps; bj-mg 62.0 and 6.8 s, pfmg 51.1 and
  // 12.7 s), hypre's PFMG beyond (its iterations do not grow with the rank count;
  // docs/scale_out.md).
  if (preconditioner == "auto") preconditioner = comm_.size() <= 4 || !air_mpi::have_pfmg() ? "as-mg2" : "pfmg";
  comm_.together("air set-up", false, [&] {
    blocks_ = std::make_unique<air_mpi::GridBlocks>(air.grid.n(), starts_, comm_.rank());
    if (blocks_->dims() != d_->dims()) throw Error("air blocks and parcel blocks disagree (internal)");
  });
  sync_ = std::make_unique<air_mpi::HaloSync>(comm_.comm(), *blocks_, air.grid, air.fluid.bc);
  AirShare s;
  s.grid = sync_->local_grid();
  s.fluid = air.fluid;
  s.fluid.bc = sync_->local_bc();
  s.exchange = air.exchange;
  s.exchange.bc = sync_->local_bc();
  s.sync = sync_.get();
  s.first_cell = blocks_->lo();
  s.pressure_text = "pressure: distributed PCG + " + preconditioner;
  air_mpi::DistOptions opt;
  opt.preconditioner = preconditioner;
  opt.rel_tol = air.fluid.pressure.rel_tol;
  opt.max_iter = air.fluid.pressure.max_iter;
  comm_.together("air set-up", false, [&] {
    s.pressure = std::make_unique<air_mpi::DistPressureSolver>(comm_.comm(), *blocks_,
                                                               fluid::pressure_grid(air.grid, air.fluid), opt);
  });
  return s;
}

const fluid::FluidState& MpiDomain::gather(const fluid::FluidState& local, fluid::FluidState& whole) {
  whole.grid = grid_;
  whole.t = local.t;
  for (int q = 0; q < 3; ++q) whole.vel(q) = air_mpi::gather_field(comm_.comm(), *blocks_, local.vel(q), q);
  whole.p = air_mpi::gather_field(comm_.comm(), *blocks_, local.p, air_mpi::kCellCentred);
  whole.eps = air_mpi::gather_field(comm_.comm(), *blocks_, local.eps, air_mpi::kCellCentred);
  whole.eps_old = air_mpi::gather_field(comm_.comm(), *blocks_, local.eps_old, air_mpi::kCellCentred);
  return whole;
}

const fluid::Field& MpiDomain::gather_cells(const fluid::Field& local, fluid::Field& whole) {
  const fluid::Field zeros = local.empty() ? fluid::make_cell_field(sync_->local_grid()) : fluid::Field{};
  whole = air_mpi::gather_field(comm_.comm(), *blocks_, local.empty() ? zeros : local, air_mpi::kCellCentred);
  return whole;
}

void MpiDomain::take(const fluid::FluidState& whole, fluid::FluidState& local) {
  local.t = whole.t;
  for (int q = 0; q < 3; ++q) copy_block(*blocks_, whole.vel(q), local.vel(q));
  copy_block(*blocks_, whole.p, local.p);
  copy_block(*blocks_, whole.eps, local.eps);
  copy_block(*blocks_, whole.eps_old, local.eps_old);
}

std::string MpiDomain::describe() const {
  std::string cut_text;
  for (int a = 0; a < 3; ++a)
    if (d_->dims()[a] > 1) {
      cut_text += fmt::format(", {} cut at", "xyz"[a]);
      for (int m = 1; m < d_->dims()[a]; ++m) cut_text += fmt::format(" {:.4g}", 1e3 * d_->cuts()[a][m]);
      cut_text += " mm";
    }
  if (!cut_text.empty())
    cut_text += with_air_ ? " (balanced on the parcels, on cell faces)" : " (balanced on the parcels)";
  return fmt::format("MPI: {} ranks, blocks {} x {} x {} of the domain{}", comm_.size(), d_->dims()[0], d_->dims()[1],
                     d_->dims()[2], cut_text);
}

// The ranks' own shares of the work, for the balance lines.
std::string MpiDomain::report(const DemSolver& dem, long air_cells) {
  const long owned = static_cast<long>(dem.owned());
  const auto parcels = comm_.min_max(owned);
  const auto cells = comm_.min_max(air_cells);
  const long present = comm_.sum(owned);
  std::string s = dist_->timers().table("inside 'neighbour lists': exchanges (rank 0)");
  if (with_air_) s += fmt::format("air cells per rank: {} .. {}\n", cells[0], cells[1]);
  s += fmt::format("parcels per rank: {} .. {} (mean {:.0f})\n", parcels[0], parcels[1],
                   double(present) / comm_.size());
  return s;
}

}  // namespace cgdem::run
