// The DEM step over MPI ranks (issue 6, item 1: ghost parcels and cross-rank pairs)
// against the single-process run of the same system.
//
// System: 1,521 parcels (l = 3, d = 375 um, friction 0.4, e 0.7) on a loose 13 x 13 x 9
// lattice (1.005 d apart) in a 5 x 5 mm box with four walls and a floor, every parcel with
// its own velocity (up to 0.1 m/s per component, from its id), under 10 g so that the gas
// collapses into a bed within the 4,000 steps (4 ms): about 30 list builds, ~1,300
// contacts at the end, and parcels cross the cuts (x = 2.5 mm, and y = 2.5 mm on 4 ranks)
// while in contact with parcels of the other side.
//
// Every rank runs the plain DemSolver on the whole system (the reference) in step with the
// distributed one (its own block, with ghosts), and compares its own parcels by id. Rank
// 0 also runs the reference with the parcels added in reverse order: the same physics in
// another summation order, the yardstick of what round-off alone does to this flow.
//   * 1 rank: no ghosts; the distributed run is the serial one bit for bit (every field
//     of every parcel, every pair and wall history, the energy totals).
//   * 2 and 4 ranks: parcel count and id checksum exact, mass to 1e-14. A parcel's contact
//     forces are added in the order of its rank's lists, not of the serial lists, so they
//     differ in the last bit from the first step on, and the flow amplifies that (about
//     1e-17 m at step 100, 1e-15 m at 1,000, 1e-5 m at 4,000, for the reverse-order serial
//     run as much as for the distributed one). Checked: positions within 1e-12 m and
//     velocities within 1e-7 m/s at steps 100 and 1,000, while the difference is still
//     round-off (a missing or wrong contact force gives dt^2 |F| / m ~ 1e-8 m and
//     dt |F| / m ~ 1e-3 m/s in one step); at the end, what the amplified round-off leaves:
//     positions within 0.25 d, momentum within 2e-2 of M u0, kinetic energy within 10 %,
//     dissipated energy within 1 % (measured values printed, with the reverse-order run's).
//   * Split pairs (an owned parcel and a ghost) exist and touch; each is listed on both of
//     its ranks with histories that are exact negations (equal values in the lower id's
//     frame); records that reached a rank twice are equal.
// And: escaped parcels are removed and counted over the ranks; periodic axes are refused.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "../mpi_util.hpp"
#include "../parallel_test_util.hpp"
#include "solvers/dem_mpi/distributed_dem.hpp"

namespace cgdem::parallel {
namespace {

using test::reduced;
using test::world_rank;
using test::world_size;

const Species kS = test::powder_l3();  // d = 375 um parcels of 125 um originals
const double kD = kS.diameter();
constexpr double kL = 5e-3;  // box side [m]
constexpr int kNx = 13, kNy = 13, kNz = 9;
constexpr long kSteps = 4000;
constexpr double kU = 0.1;  // initial velocity scale [m/s]
constexpr double kG = 100;  // gravity [m/s^2]: the bed forms within the 4 ms simulated

geometry::Scene box_scene() {
  geometry::Scene scene;
  const int b = scene.add_body("box", geometry::Motion{});
  scene.add_part(b, "x0", geometry::make_half_space({0, 0, 0}, {1, 0, 0}));
  scene.add_part(b, "x1", geometry::make_half_space({kL, 0, 0}, {-1, 0, 0}));
  scene.add_part(b, "y0", geometry::make_half_space({0, 0, 0}, {0, 1, 0}));
  scene.add_part(b, "y1", geometry::make_half_space({0, kL, 0}, {0, -1, 0}));
  scene.add_part(b, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  return scene;
}

DemParams params() {
  DemParams p;
  p.dt = 1e-6;
  p.gravity = {0, 0, -kG};
  p.domain = {{-1e-3, -1e-3, -1e-3}, {kL + 1e-3, kL + 1e-3, 12e-3}};
  return p;
}

DemSolver make_solver() { return DemSolver({kS}, MaterialParams{50, 0.7, 0.4, 0.7, 0.4}, params(), box_scene()); }

// A number in [-1, 1) from (id, k) (splitmix64): each parcel's velocity, the same on every rank.
double hashed(uint64_t id, uint64_t k) {
  uint64_t z = id * 0x9E3779B97F4A7C15ull + k * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
}

struct Seed {
  int64_t id;
  Vec3 x, v;
};
std::vector<Seed> seeds() {
  std::vector<Seed> s;
  const double a = 1.005 * kD;  // lattice spacing
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        const int64_t id = i + kNx * (j + kNy * k);
        const uint64_t u = static_cast<uint64_t>(id);
        s.push_back({id, {0.2e-3 + i * a, 0.2e-3 + j * a, 0.19e-3 + k * a},
                     {kU * hashed(u, 0), kU * hashed(u, 1), kU * hashed(u, 2)}});
      }
  return s;
}

Decomposition decomposition() {
  const int n = world_size();
  return Decomposition(params().domain, n == 4 ? Dims{2, 2, 1} : Dims{n, 1, 1});
}

bool same_bits(const void* a, const void* b, size_t n) { return std::memcmp(a, b, n) == 0; }
template <class T>
bool same_vector(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || same_bits(a.data(), b.data(), a.size() * sizeof(T)));
}

// Differences of this rank's owned parcels from the reference, by id; over all ranks
// (collective) unless `local`.
struct Diff {
  double dx = 0, dv = 0, dw = 0;  // max |x - x_ref| [m], |v - v_ref| [m/s], |omega - omega_ref| [1/s]
  long missing = 0;               // owned parcels the reference does not have
};
Diff compare(const DemSolver& dist, const DemSolver& ref, bool local = false) {
  const Particles& p = dist.particles();
  const Particles& r = ref.particles();
  int64_t max_id = 0;  // ids are small and >= 0 here
  for (const int64_t id : r.id) max_id = std::max(max_id, id);
  std::vector<int> at(max_id + 1, -1);
  for (size_t i = 0; i < r.size(); ++i) at[r.id[i]] = static_cast<int>(i);
  Diff d;
  for (size_t i = 0; i < dist.owned(); ++i) {
    const int k = p.id[i] >= 0 && p.id[i] <= max_id ? at[p.id[i]] : -1;
    if (k < 0) {
      ++d.missing;
      continue;
    }
    d.dx = std::max(d.dx, norm(p.x[i] - r.x[k]));
    d.dv = std::max(d.dv, norm(p.v[i] - r.v[k]));
    d.dw = std::max(d.dw, norm(p.omega[i] - r.omega[k]));
  }
  if (local) return d;
  d.dx = reduced(d.dx, MPI_MAX);
  d.dv = reduced(d.dv, MPI_MAX);
  d.dw = reduced(d.dw, MPI_MAX);
  d.missing = reduced(d.missing, MPI_SUM);
  return d;
}

// Every split pair of every rank: (lower id, higher id, history in the lower id's frame).
struct SplitRecord {
  int64_t a, b;
  contact::History h;
};
std::vector<SplitRecord> gathered_split_pairs(const DemSolver& dem) {
  const Particles& p = dem.particles();
  const NeighborList& nl = dem.neighbor_list();
  const size_t n = dem.owned();
  std::vector<SplitRecord> mine;
  for (size_t i = 0; i < n; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int j = nl.partner[e];
      if (static_cast<size_t>(j) < n) continue;
      mine.push_back(p.id[i] < p.id[j] ? SplitRecord{p.id[i], p.id[j], nl.hist.get(e)}
                                       : SplitRecord{p.id[j], p.id[i], nl.hist.get(e).flipped()});
    }
  const int size = world_size();
  const int bytes = static_cast<int>(mine.size() * sizeof(SplitRecord));
  std::vector<int> count(size), start(size, 0);
  MPI_Allgather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < size; ++r) start[r] = start[r - 1] + count[r - 1];
  std::vector<SplitRecord> all((start.back() + count.back()) / sizeof(SplitRecord));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), count.data(), start.data(), MPI_BYTE, MPI_COMM_WORLD);
  return all;
}

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// Equal values, component by component (+0 == -0): the two ranks' histories of a split
// pair, both in the lower id's frame.
bool same_values(const contact::History& a, const contact::History& b) {
  return a.xi.x == b.xi.x && a.xi.y == b.xi.y && a.xi.z == b.xi.z && a.ft.x == b.ft.x && a.ft.y == b.ft.y &&
         a.ft.z == b.ft.z && a.s1 == b.s1 && a.s2 == b.s2;
}

TEST(DistributedDem, MatchesTheSingleProcessRun) {
  const int rank = world_rank(), size = world_size();
  const Decomposition d = decomposition();
  // The reverse-order run is the same on every rank: rank 0 runs it (for the printout).
  DemSolver ref = make_solver(), dist = make_solver(), alt = make_solver();
  const std::vector<Seed> all = seeds();
  for (const Seed& s : all) {
    ref.particles().add(s.id, 0, kS, s.x, s.v);
    if (d.owner_of(s.x) == rank) dist.particles().add(s.id, 0, kS, s.x, s.v);
  }
  if (rank == 0)
    for (auto s = all.rbegin(); s != all.rend(); ++s) alt.particles().add(s->id, 0, kS, s->x, s->v);
  DistributedDem hook(MPI_COMM_WORLD, d, dist);
  const ParcelTotals t0 = global_totals(MPI_COMM_WORLD, dist.particles(), dist.particles().size());

  // Checkpoints: the distributed run and the reordered serial run against the reference.
  const long checkpoints[] = {100, 1000, 2000, kSteps};
  Diff at_dist[4], at_alt[4];
  long split_listed = 0, split_touching = 0, split_seen_max = 0;
  Stopwatch clock;
  for (long step = 1, c = 0; step <= kSteps; ++step) {
    dist.step();
    ref.step();
    if (rank == 0) alt.step();
    if (step == checkpoints[c]) {
      at_dist[c] = compare(dist, ref);
      if (rank == 0) at_alt[c] = compare(alt, ref, true);
      ++c;
    }
    if (step % 250 == 0) {
      const SplitPairs s = split_pairs(dist);
      const long touching = reduced(s.touching, MPI_SUM);
      split_listed += reduced(s.listed, MPI_SUM);
      split_touching += touching;
      split_seen_max = std::max(split_seen_max, touching);
    }
  }
  const double seconds = clock.seconds();
  const Diff& end = at_dist[3];
  const ParcelTotals t1 = global_totals(MPI_COMM_WORLD, dist.particles(), dist.owned());
  const EnergyBudget eg = global_energy(MPI_COMM_WORLD, dist), er = ref.energy();
  const EnergyBudget ea = rank == 0 ? alt.energy() : er;  // printed by rank 0 only
  const long contacts = global_contacts(MPI_COMM_WORLD, dist), contacts_ref = ref.contact_count();
  const long removed = global_removed(MPI_COMM_WORLD, dist);

  // Split pairs at the end: each listed on its two ranks, with histories that are exact
  // negations (equal values in the lower id's frame; a cleared history may be -0 there).
  const std::vector<SplitRecord> sp = gathered_split_pairs(dist);
  std::map<std::pair<int64_t, int64_t>, std::vector<contact::History>> by_pair;
  for (const SplitRecord& r : sp) by_pair[{r.a, r.b}].push_back(r.h);
  long pairs_twice = 0, pairs_not_twice = 0, pairs_negated = 0, pairs_with_history = 0;
  for (const auto& [ids, hs] : by_pair) {
    if (hs.size() != 2) {
      ++pairs_not_twice;
      continue;
    }
    ++pairs_twice;
    pairs_negated += same_values(hs[0], hs[1]);
    pairs_with_history += !hs[0].empty();
  }
  const auto& c = hook.counters();
  const long sent = reduced(c.parcels_sent, MPI_SUM), builds = c.builds;
  const long twice = reduced(c.records_twice, MPI_SUM), differing = reduced(c.records_differing, MPI_SUM);
  const long ghosts = reduced(c.ghosts_received, MPI_SUM);

  auto kinetic = [](const EnergyBudget& e) { return e.kinetic_translational + e.kinetic_rotational; };
  auto dissipated = [](const EnergyBudget& e) { return e.dissipated_damping + e.dissipated_friction; };
  // Momentum against the scale of the initial one, M u0: walls and floor take most of it.
  const double p_scale = er.mass * kU;
  const double dp = norm(eg.momentum - er.momentum) / p_scale, dp_alt = norm(ea.momentum - er.momentum) / p_scale;
  const double e_ke = rel(kinetic(eg), kinetic(er)), e_ke_alt = rel(kinetic(ea), kinetic(er));
  const double e_diss = rel(dissipated(eg), dissipated(er)), e_diss_alt = rel(dissipated(ea), dissipated(er));
  const double e_mass = rel(t1.mass, t0.mass);
  if (rank == 0) {
    std::printf("[ distributed ] %d rank(s), %d x %d x %d blocks: %lld parcels, %ld steps in %.2f s (with the serial "
                "run on every rank and the reverse-order one on rank 0), %ld list builds, %ld parcels migrated, %ld ghosts at the end, removed %ld\n",
                size, d.dims()[0], d.dims()[1], d.dims()[2], static_cast<long long>(t1.count), kSteps, seconds,
                builds, sent, ghosts, removed);
    std::printf("[ distributed ] split pairs (every 250 steps): %ld listed, %ld touching (at most %ld at once); at "
                "the end %zu pairs: %ld on both ranks, %ld not, %ld exact negations (%ld not empty); records that "
                "arrived twice %ld, differing %ld\n",
                split_listed, split_touching, split_seen_max, by_pair.size(), pairs_twice, pairs_not_twice,
                pairs_negated, pairs_with_history, twice, differing);
    for (int k = 0; k < 4; ++k)
      std::printf("[ distributed ] step %4ld, max over parcels: |dx| %.3e m, |dv| %.3e m/s, |dw| %.3e 1/s; serial "
                  "run in reverse parcel order: |dx| %.3e m, |dv| %.3e m/s, |dw| %.3e 1/s\n",
                  checkpoints[k], at_dist[k].dx, at_dist[k].dv, at_dist[k].dw, at_alt[k].dx, at_alt[k].dv,
                  at_alt[k].dw);
    std::printf("[ distributed ] totals: count %lld / %zu, id checksum %s, mass rel %.2e; momentum diff %.2e of M u0 "
                "(reverse order %.2e); E_kin %.6e J, rel %.2e (%.2e); dissipated %.6e J, rel %.2e (%.2e); contacts %ld "
                "/ %ld\n",
                static_cast<long long>(t1.count), ref.particles().size(),
                t1.id_checksum == t0.id_checksum ? "equal" : "DIFFERS", e_mass, dp, dp_alt, kinetic(eg), e_ke, e_ke_alt,
                dissipated(eg), e_diss, e_diss_alt, contacts, contacts_ref);
  }
  EXPECT_EQ(t0.count, static_cast<int64_t>(all.size()));
  EXPECT_EQ(t1.count, t0.count);
  EXPECT_EQ(t1.id_checksum, t0.id_checksum);
  EXPECT_EQ(end.missing, 0);
  EXPECT_EQ(removed, 0);
  EXPECT_EQ(removed, ref.removed());
  EXPECT_GT(builds, 20);
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(pairs_not_twice, 0);
  EXPECT_EQ(pairs_negated, pairs_twice);

  if (size == 1) {
    // Bitwise: the same parcels in the same order, every field, every history.
    const Particles &p = dist.particles(), &r = ref.particles();
    long fields_differ = 0;
    ASSERT_EQ(p.size(), r.size());
    for (size_t i = 0; i < p.size(); ++i) fields_differ += test::bytes_of(p, i) != test::bytes_of(r, i);
    const NeighborList &nl = dist.neighbor_list(), &nr = ref.neighbor_list();
    const bool lists_equal = same_vector(nl.offset, nr.offset) && same_vector(nl.partner, nr.partner) &&
                             same_vector(nl.hist.records(), nr.hist.records()) && same_vector(nl.wall_offset, nr.wall_offset) &&
                             same_vector(nl.wall_part, nr.wall_part) && same_vector(nl.wall_hist, nr.wall_hist);
    long live_hist = 0;
    for (const auto& h : nr.hist.records()) live_hist += !h.empty();
    const EnergyBudget e1 = dist.energy();
    std::printf("[ distributed ] 1 rank: parcels with a differing field %ld, lists and histories %s (%ld pair "
                "histories not empty), energy() %s, global_energy() %s\n",
                fields_differ, lists_equal ? "equal" : "DIFFER", live_hist,
                same_bits(&e1, &er, sizeof e1) ? "equal" : "DIFFERS",
                same_bits(&eg, &er, sizeof eg) ? "equal" : "DIFFERS");
    EXPECT_EQ(fields_differ, 0);
    EXPECT_TRUE(lists_equal);
    EXPECT_GT(live_hist, 500);
    EXPECT_TRUE(same_bits(&e1, &er, sizeof e1));
    EXPECT_TRUE(same_bits(&eg, &er, sizeof eg));
    EXPECT_EQ(contacts, contacts_ref);
    EXPECT_EQ(sent, 0);
    EXPECT_EQ(by_pair.size(), 0u);
  } else {
    EXPECT_GT(sent, 20);                // parcels crossed the cuts
    EXPECT_GT(split_touching, 300);     // and touched across them
    EXPECT_GT(pairs_with_history, 10);  // with histories on both sides
    EXPECT_LT(e_mass, 1e-14);
    // While the difference is round-off (steps 100 and 1000; a wrong force shows at once).
    for (int k = 0; k < 2; ++k) {
      EXPECT_LT(at_dist[k].dx, 1e-12) << "step " << checkpoints[k];
      EXPECT_LT(at_dist[k].dv, 1e-7) << "step " << checkpoints[k];
    }
    // At the end, amplified by the flow as much as a mere reordering of the serial run.
    EXPECT_LT(end.dx, 0.25 * kD);
    EXPECT_LT(dp, 2e-2);
    EXPECT_LT(e_ke, 0.1);
    EXPECT_LT(e_diss, 1e-2);
  }
}

// Parcels that leave the domain are removed on their rank and counted over all ranks. A
// cloud drifts and expands homologously (v = u + c (x - x_c): no two parcels meet, so there
// are no forces and every rank computes the serial bits) without gravity: many parcels
// cross the cuts, and part of the cloud leaves the domain.
TEST(DistributedDem, EscapedParcelsAreRemovedAndCountedOnEveryRank) {
  const int rank = world_rank();
  const Decomposition d = decomposition();
  DemParams prm = params();
  prm.gravity = {};
  const geometry::Scene none;
  DemSolver ref({kS}, MaterialParams{}, prm, none), dist({kS}, MaterialParams{}, prm, none);
  const Vec3 centre{0.4 * kL, 0.4 * kL, 2e-3};  // off the cuts: the cloud grows across them
  int64_t id = 0;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i, ++id) {
      const Vec3 x = centre + Vec3{(i - 5.5) * 1.12 * kD, (j - 5.5) * 1.12 * kD, 0.0};
      const Vec3 v = Vec3{0.6, 0.6, 0} + 400.0 * (x - centre);  // a drift across the cuts, and the growth
      ref.particles().add(id, 0, kS, x, v);
      if (d.owner_of(x) == rank) dist.particles().add(id, 0, kS, x, v);
    }
  DistributedDem hook(MPI_COMM_WORLD, d, dist);
  for (int step = 0; step < 2000; ++step) {
    dist.step();
    ref.step();
  }
  const ParcelTotals t = global_totals(MPI_COMM_WORLD, dist.particles(), dist.owned());
  const ParcelTotals tr = global_totals(MPI_COMM_SELF, ref.particles());
  const long removed = global_removed(MPI_COMM_WORLD, dist);
  const long sent = reduced(hook.counters().parcels_sent, MPI_SUM);
  const Diff diff = compare(dist, ref);
  if (rank == 0)
    std::printf("[ escape ] %lld parcels left of 144 (serial %lld), removed %ld (serial %ld), migrated %ld, id checksum "
                "%s, max |dx| %.3e m\n",
                static_cast<long long>(t.count), static_cast<long long>(tr.count), removed, ref.removed(), sent,
                t.id_checksum == tr.id_checksum ? "equal" : "DIFFERS", diff.dx);
  EXPECT_EQ(t.count, tr.count);
  EXPECT_EQ(t.id_checksum, tr.id_checksum);
  EXPECT_EQ(removed, ref.removed());
  EXPECT_GT(removed, 20);
  EXPECT_EQ(diff.missing, 0);
  EXPECT_EQ(diff.dx, 0.0);
  if (world_size() > 1) {
    EXPECT_GT(sent, 10);
  }
}

TEST(DistributedDem, PeriodicAxesAreRefused) {
  DemParams p = params();
  p.periodic = {false, true, false};
  DemSolver dem({kS}, MaterialParams{}, p, box_scene());
  const Decomposition d(p.domain, world_size() == 4 ? Dims{2, 2, 1} : Dims{world_size(), 1, 1});
  std::string msg = "(no error)";
  try {
    DistributedDem hook(MPI_COMM_WORLD, d, dem);
  } catch (const Error& e) {
    msg = e.what();
  }
  if (world_rank() == 0) std::printf("[ errors ] %s\n", msg.c_str());
  EXPECT_NE(msg.find("axis y is periodic"), std::string::npos) << msg;
  EXPECT_EQ(dem.domain_exchange(), nullptr);
}

}  // namespace
}  // namespace cgdem::parallel
