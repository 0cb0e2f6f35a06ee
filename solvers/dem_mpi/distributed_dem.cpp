#include "solvers/dem_mpi/distributed_dem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.hpp"
#include "parallel/mpi/exchange.hpp"
#include "parallel/parcel_fields.hpp"

namespace cgdem::parallel {

namespace {

constexpr int kGhostSizeTag = 6201, kGhostTag = 6202, kRefreshTag = 6203;
constexpr const char* kWhat = "distributed DEM";

void check(int rc, const char* call) { check_mpi(rc, call, kWhat); }

// Keeps the parcels 0..n-1 (the owned ones, before the ghosts).
void truncate(Particles& p, size_t n) {
  for_each_field(p, [n](auto& field) { field.resize(n); });
}

// Equal values, component by component (+0 == -0: a record flipped into the lower id's
// frame may carry -0 where the other has +0).
bool same_values(const contact::History& a, const contact::History& b) {
  return a.xi.x == b.xi.x && a.xi.y == b.xi.y && a.xi.z == b.xi.z && a.ft.x == b.ft.x && a.ft.y == b.ft.y &&
         a.ft.z == b.ft.z && a.s1 == b.s1 && a.s2 == b.s2;
}

// A pair's record can reach this rank twice (from each of its two ranks, when a parcel
// moved to its partner's rank): keeps one, the records ordered by their ids (stably). The two
// are equal when the two ranks evaluated the pair alike: counts the repeats and those whose
// values differ.
void keep_one_record_per_pair(std::vector<CarriedPair>& rec, long& twice, long& differing) {
  std::stable_sort(rec.begin(), rec.end(), [](const CarriedPair& a, const CarriedPair& b) {
    return a.id_a != b.id_a ? a.id_a < b.id_a : a.id_b < b.id_b;
  });
  size_t w = 0;
  for (size_t r = 0; r < rec.size(); ++r) {
    if (w > 0 && rec[w - 1].id_a == rec[r].id_a && rec[w - 1].id_b == rec[r].id_b) {
      ++twice;
      differing += !same_values(rec[w - 1].h, rec[r].h);
      continue;
    }
    rec[w++] = rec[r];
  }
  rec.resize(w);
}

}  // namespace

DistributedDem::DistributedDem(MPI_Comm comm, const Decomposition& d, DemSolver& dem)
    : comm_(comm), d_(d), dem_(dem) {
  t_vote_ = timers_.id("rebuild vote");
  t_refresh_ = timers_.id("ghost refresh");
  t_build_ = timers_.id("build exchanges");
  int size = 0;
  check(MPI_Comm_rank(comm, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  if (size != d.ranks())
    throw Error(fmt::format("distributed DEM: {} ranks run a decomposition into {} x {} x {} = {} blocks", size,
                            d.dims()[0], d.dims()[1], d.dims()[2], d.ranks()));
  const DemParams& prm = dem.params();
  for (int a = 0; a < 3; ++a)
    if (prm.periodic[a] || d.periodic()[a])
      throw Error(fmt::format("distributed DEM: axis {} is periodic; ghost parcels through periodic images are not "
                              "implemented yet (run on one process, or without periodic axes)",
                              "xyz"[a]));
  const geometry::Aabb& box = d.box();
  for (int a = 0; a < 3; ++a)
    if (!(box.lo[a] <= prm.domain.lo[a] && prm.domain.hi[a] <= box.hi[a]))
      throw Error(fmt::format("distributed DEM: the DEM domain [{:g}, {:g}] m along {} is not inside the decomposed "
                              "box [{:g}, {:g}] m: every parcel the domain keeps needs an owner",
                              prm.domain.lo[a], prm.domain.hi[a], "xyz"[a], box.lo[a], box.hi[a]));
  if (dem.domain_exchange()) throw Error("distributed DEM: the DemSolver already has a domain exchange");
  nb_ = d.neighbours(rank_);
  send_.assign(nb_.size(), {});
  recv_.assign(nb_.size(), 0);
  sbuf_.assign(nb_.size(), {});
  rbuf_.assign(nb_.size(), {});
  dem.set_domain_exchange(this);
}

DistributedDem::~DistributedDem() {
  if (dem_.domain_exchange() == this) dem_.set_domain_exchange(nullptr);
}

bool DistributedDem::any(bool local_rebuild) {
  auto scope = timers_.scope(t_vote_);
  int mine = local_rebuild ? 1 : 0, all = 0;
  check(MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LOR, comm_), "MPI_Allreduce");
  return all != 0;
}

void DistributedDem::drop_ghosts(Particles& p, NeighborList& nl) {
  auto scope = timers_.scope(t_build_);
  const size_t n_owned = nl.owned(p);
  if (nl.ghosts > 0 && (p.size() != n_total_ || n_owned != n_owned_))
    throw Error(fmt::format("distributed DEM: rank {} holds {} particles, {} of them ghosts, but its last build left "
                            "{} owned and {} ghosts (parcels added between steps? add them before the first step)",
                            rank_, p.size(), nl.ghosts, n_owned_, n_total_ - n_owned_));
  // Split pairs: the history (in the owned parcel's frame, the owner) as a record by id,
  // in the lower id's frame. The pair's other rank keeps the same record.
  if (nl.valid_for(p))
    for (size_t i = 0; i < n_owned; ++i)
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int j = nl.partner[e];
        if (static_cast<size_t>(j) < n_owned || nl.hist.empty(e)) continue;
        const contact::History h = nl.hist.get(e);
        nl.incoming.pairs.push_back(p.id[i] < p.id[j] ? CarriedPair{p.id[i], p.id[j], h}
                                                       : CarriedPair{p.id[j], p.id[i], h.flipped()});
        ++counters_.records_split;
      }
  if (nl.ghosts > 0) {
    std::vector<int> keep(n_owned);
    std::iota(keep.begin(), keep.end(), 0);
    nl.retain(keep, 0);  // the owned parcels' pairs and wall contacts; ghosts = 0
    truncate(p, n_owned);
  }
  nl.ghosts = 0;
}

void DistributedDem::select_ghosts(const Particles& p, size_t n_owned) {
  for (size_t k = 0; k < nb_.size(); ++k) {
    const geometry::Aabb block = d_.block(nb_[k]);
    std::vector<std::pair<int64_t, int>> near;
    for (size_t i = 0; i < n_owned; ++i)
      if (block.distance(p.x[i]) < range_) near.emplace_back(p.id[i], static_cast<int>(i));
    std::sort(near.begin(), near.end());  // id order: the same before and after the build's sort
    send_[k].resize(near.size());
    for (size_t m = 0; m < near.size(); ++m) send_[k][m] = near[m].second;
  }
}

void DistributedDem::rebuild(Particles& p, NeighborList& nl, const geometry::Scene::Frame& walls) {
  auto scope = timers_.scope(t_build_);
  if (nl.ghosts != 0) throw Error("distributed DEM: rebuild() before drop_ghosts()");
  ++counters_.builds;
  // 1. Every parcel to the rank of its block, with its histories.
  const MigrationCounts mc = migrate(comm_, d_, p, nl);
  counters_.parcels_sent += mc.sent.parcels;
  counters_.records_sent += mc.sent.pairs + mc.sent.walls;

  // 2. Ghosts: the parcels within one interaction range of each neighbour's block. A pair
  //    is listed when |x_a - x_b| < r_a + r_b + skin, and a parcel of this block is no
  //    further from it than that: 2 r_max + skin (r_max over all ranks) finds them all.
  const size_t n_owned = p.size();
  double rmax = 0;
  for (size_t i = 0; i < n_owned; ++i) rmax = std::max(rmax, p.radius[i]);
  check(MPI_Allreduce(MPI_IN_PLACE, &rmax, 1, MPI_DOUBLE, MPI_MAX, comm_), "MPI_Allreduce");
  range_ = 2 * rmax + nl.skin;
  select_ghosts(p, n_owned);
  std::vector<Buffer> out(nb_.size());
  for (size_t k = 0; k < nb_.size(); ++k) out[k] = pack_copies(p, send_[k]);
  raise_together(comm_, rank_, oversized(out, nb_, kWhat), kWhat);
  const std::vector<Buffer> in = exchange_buffers(comm_, nb_, out, kGhostSizeTag, kGhostTag, kWhat);

  // 3. Ghosts appended after the owned parcels, in neighbour order; the lists follow (the
  //    owned parcels' histories stay, the ghosts have none); the build attaches the records.
  std::string error;
  try {
    size_t n_ghosts = 0;
    for (size_t k = 0; k < nb_.size(); ++k) n_ghosts += recv_[k] = static_cast<int>(unpack_arriving(in[k], p, nl));
    std::vector<int> keep(n_owned);
    std::iota(keep.begin(), keep.end(), 0);
    nl.retain(keep, n_ghosts);
    nl.ghosts = n_ghosts;
    counters_.ghosts_received = static_cast<long>(n_ghosts);
    keep_one_record_per_pair(nl.incoming.pairs, counters_.records_twice, counters_.records_differing);
    nl.build(p, walls);
  } catch (const Error& e) {
    error = e.what();
  }
  raise_together(comm_, rank_, error, kWhat);

  // 4. The build sorted the owned parcels: find the ones each neighbour holds again.
  reselect_ghosts(p, n_owned);
}

void DistributedDem::reselect_ghosts(const Particles& p, size_t n_owned) {
  std::vector<size_t> sent(nb_.size());
  for (size_t k = 0; k < nb_.size(); ++k) sent[k] = send_[k].size();
  select_ghosts(p, n_owned);
  for (size_t k = 0; k < nb_.size(); ++k)
    if (send_[k].size() != sent[k])
      throw Error(fmt::format("distributed DEM: rank {} sent rank {} {} ghosts, but finds {} after its build", rank_,
                              nb_[k], sent[k], send_[k].size()));
  n_owned_ = n_owned;
  n_total_ = p.size();
  for (size_t k = 0; k < nb_.size(); ++k) {
    sbuf_[k].resize(9 * send_[k].size());
    rbuf_[k].resize(9 * static_cast<size_t>(recv_[k]));
  }
}

void DistributedDem::refresh_ghosts(Particles& p) {
  auto scope = timers_.scope(t_refresh_);
  if (p.size() != n_total_)
    throw Error(fmt::format("distributed DEM: rank {} holds {} particles, its last build {} (parcels added between "
                            "steps? add them before the first step)",
                            rank_, p.size(), n_total_));
  const int n = static_cast<int>(nb_.size());
  std::vector<MPI_Request> req;
  req.reserve(2 * n);
  for (int k = 0; k < n; ++k) {
    if (recv_[k] == 0) continue;
    req.emplace_back();
    check(MPI_Irecv(rbuf_[k].data(), static_cast<int>(rbuf_[k].size()), MPI_DOUBLE, nb_[k], kRefreshTag, comm_,
                    &req.back()),
          "MPI_Irecv");
  }
  for (int k = 0; k < n; ++k) {
    if (send_[k].empty()) continue;
    double* b = sbuf_[k].data();
    for (const int i : send_[k]) {
      for (const Vec3* f : {&p.x[i], &p.v[i], &p.omega[i]}) {
        *b++ = f->x;
        *b++ = f->y;
        *b++ = f->z;
      }
    }
    req.emplace_back();
    check(MPI_Isend(sbuf_[k].data(), static_cast<int>(sbuf_[k].size()), MPI_DOUBLE, nb_[k], kRefreshTag, comm_,
                    &req.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  size_t g = n_owned_;
  for (int k = 0; k < n; ++k) {
    const double* b = rbuf_[k].data();
    for (int m = 0; m < recv_[k]; ++m, ++g)
      for (Vec3* f : {&p.x[g], &p.v[g], &p.omega[g]}) {
        f->x = *b++;
        f->y = *b++;
        f->z = *b++;
      }
  }
}

EnergyBudget global_energy(MPI_Comm comm, const DemSolver& dem) {
  // DemSolver::energy() covers the owned parcels, a pair with a ghost on the lower id's rank.
  const EnergyBudget b = dem.energy();
  double v[] = {b.kinetic_translational, b.kinetic_rotational, b.kinetic_rotational_originals, b.potential,
                b.elastic, b.dissipated_damping, b.dissipated_friction, b.work_walls, b.momentum.x, b.momentum.y,
                b.momentum.z, b.mass};
  check(MPI_Allreduce(MPI_IN_PLACE, v, std::size(v), MPI_DOUBLE, MPI_SUM, comm), "MPI_Allreduce");
  EnergyBudget g;
  g.kinetic_translational = v[0], g.kinetic_rotational = v[1], g.kinetic_rotational_originals = v[2];
  g.potential = v[3], g.elastic = v[4], g.dissipated_damping = v[5], g.dissipated_friction = v[6];
  g.work_walls = v[7], g.momentum = {v[8], v[9], v[10]}, g.mass = v[11];
  return g;
}

long global_contacts(MPI_Comm comm, const DemSolver& dem) {
  long c = dem.contact_count();
  check(MPI_Allreduce(MPI_IN_PLACE, &c, 1, MPI_LONG, MPI_SUM, comm), "MPI_Allreduce");
  return c;
}

long global_removed(MPI_Comm comm, const DemSolver& dem) {
  long c = dem.removed();
  check(MPI_Allreduce(MPI_IN_PLACE, &c, 1, MPI_LONG, MPI_SUM, comm), "MPI_Allreduce");
  return c;
}

SplitPairs split_pairs(const DemSolver& dem) {
  const Particles& p = dem.particles();
  const NeighborList& nl = dem.neighbor_list();
  const size_t n = dem.owned();
  SplitPairs s;
  if (!nl.valid_for(p)) return s;
  for (size_t i = 0; i < n; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int j = nl.partner[e];
      if (static_cast<size_t>(j) < n) continue;
      ++s.listed;
      const double r = p.radius[i] + p.radius[j];
      s.touching += norm2(p.x[i] - nl.partner_x(p, e)) < r * r;
    }
  return s;
}

}  // namespace cgdem::parallel
