// Force pass of the DEM step: contacts with neighbours and walls, gravity, external force,
// for the contact law of the case (contact/laws.hpp; the pass is instantiated per law).
//   reads  x, v, omega, radius, species, f_ext, neighbour lists, wall frame
//   writes force, torque, contact histories, per-particle energy accounts (when kept:
//          DemParams::accounts; without them the pass reads and writes only the springs
//          xi of the pair histories and books no energy, and the forces are the same bits)
//
// Pass 1, per block of kBlock owners (evaluate_block):
//   block_entries        the owner (and periodic shift) of every entry of the block
//   select_active        the entries in contact or with a live history; their histories
//                        (or, without the accounts, their springs) copied to a block buffer
//   evaluate_active      the vectorized pair kernel over those entries (pair_kernels.hpp)
//   unbook_split_pairs   (MPI) a pair with a ghost is booked on the rank of its lower id
//   store_active         histories and liveness back to the lists, partner shares out
//   owner_sums           per owner: gravity, f_ext, its pair shares, its wall contacts
// Pass 2 (add_partner_shares): per particle, the shares it received as a partner.
//
// Bit-reproducibility for any number of threads: there are no shared writes, and every
// sum has a fixed order. The owner sums its shares in entry order. The partner's shares
// are summed in entry order too: directly, when one thread evaluates all of that
// partner's entries (every particle on 1 thread; all but those near a chunk boundary on
// several), or else stored at the entry's place in the reverse index and summed in pass 2.
// Every entry skipped by select_active would have given zero shares and kept its empty
// history; +0 added to a sum that starts at +0 changes nothing, so the result is the same
// bits as evaluating every entry into pass 2.
// The energy a pair dissipates is booked to its owner. A pair with a ghost (MPI runs) is
// evaluated on both ranks, each keeping the force on its own parcel (the law gives the
// partner's side exactly negated); its energy is booked once, on the rank of its lower id.
// No floating-point contraction (the AVX2/AVX-512 builds of the kernel would otherwise
// fuse multiply-adds): every build computes the same bits as the baseline one.
#pragma GCC optimize("fp-contract=off")
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/dem/dem_solver.hpp"
#include "solvers/dem/pair_kernels.hpp"

namespace cgdem {

namespace {

using forces::ActiveEntries;
using forces::PairArrays;

constexpr int kBlock = 128;  // owners per block of the pair pass

// One thread's buffers for one block (grown, never shrunk): per entry of the block
// (index e - e0), then per active entry (index k).
struct BlockBuffers {
  std::vector<int> owner, starts, active, ent, own, touching, kstart;
  std::vector<double> shift[3], ashift[3], zero;
  std::vector<double> damp, fric;
  std::vector<contact::History> h;
  std::vector<Vec3> xi;
  std::vector<Vec3> fp, tp;
  BlockBuffers() { kstart.resize(kBlock + 1); }
  void fit(int ne, bool periodic) {
    if (starts.size() >= static_cast<size_t>(ne) + 1) return;
    starts.resize(ne + 1);
    for (auto* vec : {&owner, &active, &ent, &own, &touching}) vec->resize(ne);
    zero.resize(ne);  // stays 0
    damp.resize(ne);
    fric.resize(ne);
    h.resize(ne);
    xi.resize(ne);
    fp.resize(ne);
    tp.resize(ne);
    if (periodic)
      for (int k = 0; k < 3; ++k) shift[k].resize(ne), ashift[k].resize(ne);
  }
};

// The block b: owners i0..i1-1, list entries e0..e1-1.
struct Block {
  int i0, i1, e0, e1;
  int entries() const { return e1 - e0; }
};

// What an owner accumulates, in this order: gravity and f_ext, its pair shares, its walls.
struct OwnerSums {
  Vec3 f, torque;
  double e_damp = 0, e_fric = 0, w_wall = 0;
};

template <class Law, bool Accounts>
class ForcePass {
 public:
  ForcePass(Particles& p, NeighborList& nl, const geometry::Scene::Frame& frame, const contact::LawTable<Law>& table,
            const DemParams& params)
      : p_(p), nl_(nl), frame_(frame), table_(table), dt_(params.dt), g_(params.gravity),
        n_(static_cast<int>(p.size())), n_owned_(static_cast<int>(nl.owned(p))), nblocks_((n_ + kBlock - 1) / kBlock),
        periodic_(nl.periodic.any()),
        uniform_radius_(std::all_of(p.radius.begin(), p.radius.end(), [&p](double r) { return r == p.radius[0]; })),
        arrays_{p.x.data(), p.v.data(), p.omega.data(), p.radius.data(), nl.partner.data()} {}

  void run() {
#pragma omp parallel if (n_ >= 512)
    {
      const int team = omp_get_num_threads(), tid = omp_get_thread_num();
      // The same for every thread: direct_team changes only after the barriers below.
      if (nl_.direct_team != team) {
#pragma omp single
        assign_direct_partners(team);  // (implicit barrier)
        // An entry whose partner changes kind must not leave an old share behind.
        const long ne = static_cast<long>(nl_.f_partner.size());
#pragma omp for schedule(static)
        for (long k = 0; k < ne; ++k) nl_.f_partner[k] = nl_.t_partner[k] = Vec3{};
#pragma omp single nowait
        nl_.direct_team = team;
      }
      BlockBuffers buf;
      for (int b = chunk(tid, team); b < chunk(tid + 1, team); ++b) evaluate_block(block(b), buf);
#pragma omp barrier
#pragma omp for schedule(static)
      for (int j = 0; j < n_; ++j) add_partner_shares(j);
    }
  }

 private:
  // Thread t evaluates the blocks chunk(t) .. chunk(t + 1) - 1, owners in order.
  int chunk(int t, int team) const { return static_cast<int>(static_cast<long>(nblocks_) * t / team); }
  Block block(int b) const {
    const int i0 = b * kBlock, i1 = std::min(n_, i0 + kBlock);
    return {i0, i1, nl_.offset[i0], nl_.offset[i1]};
  }

  // Reads first_owner, last_owner; writes direct (per particle). Particle j is direct when
  // its lowest and highest owners (hence all of them) are in one thread's chunk: that
  // thread then adds j's shares in entry order into f_acc, which is the sum pass 2 would
  // form. Runs once per team size and lists; run() then clears the stored shares.
  void assign_direct_partners(int team) {
    std::vector<int> chunk_of(nblocks_);
    for (int t = 0; t < team; ++t)
      for (int b = chunk(t, team); b < chunk(t + 1, team); ++b) chunk_of[b] = t;
    nl_.direct.resize(n_);
    for (int j = 0; j < n_; ++j)
      nl_.direct[j] = nl_.first_owner[j] < 0 ||
                      chunk_of[nl_.first_owner[j] / kBlock] == chunk_of[nl_.last_owner[j] / kBlock];
  }

  void evaluate_block(const Block& bl, BlockBuffers& buf) {
    buf.fit(bl.entries(), periodic_);
    block_entries(bl, buf);
    const int na = select_active(bl, buf);
    evaluate_active(buf, na);
    if (Accounts && n_owned_ < n_) unbook_split_pairs(buf, na);
    store_active(buf, na);
    for (int i = bl.i0; i < bl.i1; ++i) owner_sums(i, bl.i0, buf);
  }

  // Reads offset, image; writes buf.owner[e - e0] (the owner of entry e, found without
  // branches: count the owners that start at each entry) and, on periodic axes, buf.shift.
  void block_entries(const Block& bl, BlockBuffers& buf) const {
    const int* offset = nl_.offset.data();
    const int ne = bl.entries();
    std::fill(buf.starts.begin(), buf.starts.begin() + ne + 1, 0);
    for (int i = bl.i0 + 1; i < bl.i1; ++i) ++buf.starts[offset[i] - bl.e0];
    for (int e = 0, i = bl.i0; e < ne; ++e) buf.owner[e] = i += buf.starts[e];
    if (periodic_)
      for (int e = bl.e0; e < bl.e1; ++e)
        for (int k = 0; k < 3; ++k) buf.shift[k][e - bl.e0] = nl_.shift[nl_.image[e]][k];
  }

  // Reads x, radius, live, hist; writes the active entries in entry order (buf.ent, own,
  // ashift), a copy of their histories (buf.h: whole records, cheaper than the kernel
  // gathering them lane by lane; without the accounts buf.xi, their springs) and
  // buf.kstart, the first active entry of each owner. Returns their number.
  int select_active(const Block& bl, BlockBuffers& buf) const {
    const double* zero = buf.zero.data();
    const double* shift_k[3] = {zero, zero, zero};
    if (periodic_)
      for (int k = 0; k < 3; ++k) shift_k[k] = buf.shift[k].data();
    if (uniform_radius_)
      forces::screen_entries<true>(arrays_, bl.e0, bl.e1, buf.owner.data(), shift_k, nl_.live.data(),
                                   buf.active.data(), p_.radius[0] + p_.radius[0]);
    else
      forces::screen_entries<false>(arrays_, bl.e0, bl.e1, buf.owner.data(), shift_k, nl_.live.data(),
                                    buf.active.data(), 0.0);
    const int ne = bl.entries();
    int na = 0;
    for (int e = 0; e < ne; ++e) {
      buf.ent[na] = e + bl.e0;
      buf.own[na] = buf.owner[e];
      na += buf.active[e];
    }
    const Vec3* xi = nl_.hist.xi.data();
    const contact::HistoryStore::Rest* rest = nl_.hist.rest.data();
    std::fill(buf.kstart.begin(), buf.kstart.begin() + (bl.i1 - bl.i0) + 1, 0);
    constexpr int kAhead = 8;  // records prefetched ahead of the copy (its loads miss otherwise)
    for (int k = 0; k < na; ++k) {
      const int e = buf.ent[k];
      if (k + kAhead < na) {
        __builtin_prefetch(&xi[buf.ent[k + kAhead]]);
        if constexpr (Accounts) __builtin_prefetch(&rest[buf.ent[k + kAhead]]);
      }
      if constexpr (Accounts)
        buf.h[k] = {xi[e], rest[e].ft, rest[e].s1, rest[e].s2};
      else
        buf.xi[k] = xi[e];
      ++buf.kstart[buf.own[k] - bl.i0 + 1];
    }
    for (int i = 0; i < bl.i1 - bl.i0; ++i) buf.kstart[i + 1] += buf.kstart[i];
    if (periodic_)
      for (int k = 0; k < na; ++k)
        for (int c = 0; c < 3; ++c) buf.ashift[c][k] = buf.shift[c][buf.ent[k] - bl.e0];
    return na;
  }

  // The pair kernel over the active entries: reads buf.h, writes buf.h, fp, tp, damp,
  // fric, touching (pair_kernels.hpp).
  void evaluate_active(BlockBuffers& buf, int na) const {
    const double* zero = buf.zero.data();
    const double* s[3] = {zero, zero, zero};
    if (periodic_)
      for (int k = 0; k < 3; ++k) s[k] = buf.ashift[k].data();
    const ActiveEntries act{buf.ent.data(),  buf.own.data(),  s[0],          s[1],
                            s[2],            buf.h.data(),    buf.xi.data(), buf.fp.data(),
                            buf.tp.data(),   buf.damp.data(), buf.fric.data(), buf.touching.data()};
    if (table_.species_count() == 1)
      forces::pair_kernel_one_species<Law, Accounts>(arrays_, act, na, dt_, table_.pair(0, 0));
    else
      forces::pair_kernel_species<Law, Accounts>(arrays_, act, na, dt_, table_, p_.species.data());
  }

  // MPI runs: zeroes the energy of a pair with a ghost whose lower id is the ghost's (that
  // pair is booked on the ghost's rank).
  void unbook_split_pairs(BlockBuffers& buf, int na) const {
    for (int k = 0; k < na; ++k) {
      const int j = nl_.partner[buf.ent[k]];
      if (j >= n_owned_ && p_.id[j] < p_.id[buf.own[k]]) buf.damp[k] = buf.fric[k] = 0;
    }
  }

  // Writes back hist, live (per active entry) and the partner's share: summed into f_acc,
  // t_acc (this thread evaluates all of the partner's entries, in entry order) or stored
  // at its place rev_pos[e] in the reverse index for pass 2.
  void store_active(const BlockBuffers& buf, int na) {
    const int *partner = nl_.partner.data(), *rev_pos = nl_.rev_pos.data();
    const uint8_t* direct = nl_.direct.data();
    Vec3* xi = nl_.hist.xi.data();
    contact::HistoryStore::Rest* rest = nl_.hist.rest.data();
    uint8_t* live = nl_.live.data();
    Vec3 *f_acc = nl_.f_acc.data(), *t_acc = nl_.t_acc.data();
    Vec3 *f_share = nl_.f_partner.data(), *t_share = nl_.t_partner.data();
    for (int k = 0; k < na; ++k) {
      const int e = buf.ent[k], j = partner[e];
      if constexpr (Accounts) {
        const contact::History& h = buf.h[k];
        xi[e] = h.xi;
        rest[e] = {h.ft, h.s1, h.s2};
      } else {
        xi[e] = buf.xi[k];
      }
      live[e] = static_cast<uint8_t>(buf.touching[k]);
      if (direct[j]) {
        f_acc[j] += buf.fp[k];
        t_acc[j] += buf.tp[k];
      } else {
        f_share[rev_pos[e]] = buf.fp[k];
        t_share[rev_pos[e]] = buf.tp[k];
      }
    }
  }

  // Owner i: writes force, torque (overwritten) and adds to its energy accounts; its pair
  // shares are buf's entries kstart[i - i0] .. kstart[i - i0 + 1] - 1, in entry order.
  void owner_sums(int i, int i0, const BlockBuffers& buf) {
    const double ri = p_.radius[i];
    OwnerSums s;
    s.f = (1.0 / p_.inv_mass[i]) * g_ + p_.f_ext[i];
    for (int k = buf.kstart[i - i0]; k < buf.kstart[i - i0 + 1]; ++k) {
      s.f -= buf.fp[k];
      s.torque -= ri * buf.tp[k];  // (-r_i n) x F_t
      if constexpr (Accounts) {
        s.e_damp += buf.damp[k];
        s.e_fric += buf.fric[k];
      }
    }
    wall_contacts(i, s);
    p_.force[i] = s.f;
    p_.torque[i] = s.torque;
    if constexpr (Accounts) {
      p_.e_damping[i] += s.e_damp;
      p_.e_friction[i] += s.e_fric;
      p_.w_walls[i] += s.w_wall;
    }
  }

  // Owner i's wall candidates in order: reads the wall frame, writes wall_hist, adds to s.
  void wall_contacts(int i, OwnerSums& s) {
    const double ri = p_.radius[i];
    const Vec3 xi = p_.x[i], vi = p_.v[i], wi = p_.omega[i];
    const typename Law::Params& c = table_.wall(p_.species[i]);
    for (int e = nl_.wall_offset[i]; e < nl_.wall_offset[i + 1]; ++e) {
      const int part = nl_.wall_part[e];
      Vec3 grad;
      const double dist = frame_.part_distance(part, xi, grad);  // eq. (15): phi, grad phi
      if (dist >= ri && nl_.wall_hist[e].empty()) continue;
      const double gl = norm(grad);
      const Vec3 nrm = (1.0 / gl) * grad;
      const Vec3 u_wall = frame_.part_velocity(part);
      const Vec3 v_rel = (vi - u_wall) - cross(ri * wi, nrm);
      typename Law::History h = Law::unpack(nl_.wall_hist[e]);
      contact::Work w;
      if (dist >= ri) {  // the contact has just ended
        Law::finish(c, nrm, v_rel, h, dt_, w);  // (clears h)
        nl_.wall_hist[e] = Law::pack(h);
        s.e_damp += w.damping_n;
        s.e_fric += w.friction;
        continue;
      }
      // eq. (16)-(17): overlap (d/2 - phi) along grad phi, scaled by |grad phi| (= 1 for exact SDFs)
      const double delta = (ri - dist) * gl;
      Vec3 f_t;
      const Vec3 fc = Law::force(c, nrm, delta, v_rel, h, dt_, f_t, w);
      nl_.wall_hist[e] = Law::pack(h);
      s.f += fc;
      s.torque += cross(-ri * nrm, f_t);
      s.e_damp += w.damping_n;
      s.e_fric += w.friction;
      s.w_wall += dot(fc, u_wall) * dt_;  // power of the contact force at the wall's velocity
    }
  }

  // Pass 2, particle j: adds the shares it received as a partner, in increasing entry
  // order (summed already when direct, else stored in that order); clears f_acc, t_acc.
  void add_partner_shares(int j) {
    Vec3 f{}, t{};
    if (nl_.direct[j]) {
      f = nl_.f_acc[j], t = nl_.t_acc[j];
      nl_.f_acc[j] = Vec3{}, nl_.t_acc[j] = Vec3{};
    } else {
      for (int k = nl_.rev_offset[j]; k < nl_.rev_offset[j + 1]; ++k) {
        f += nl_.f_partner[k];
        t += nl_.t_partner[k];
      }
    }
    p_.force[j] += f;
    p_.torque[j] -= p_.radius[j] * t;
  }

  Particles& p_;
  NeighborList& nl_;
  const geometry::Scene::Frame& frame_;
  const contact::LawTable<Law>& table_;
  const double dt_;
  const Vec3 g_;
  const int n_, n_owned_, nblocks_;
  const bool periodic_;
  const bool uniform_radius_;  // every particle (ghosts too) has the same radius
  const PairArrays arrays_;
};

}  // namespace

void DemSolver::compute_forces() {
  auto scope = timers_.scope(t_force_);
  std::visit(
      [this](const auto& table) {
        using Law = typename std::decay_t<decltype(table)>::Law;
        if (params_.accounts)
          ForcePass<Law, true>(p_, nl_, frame_, table, params_).run();
        else
          ForcePass<Law, false>(p_, nl_, frame_, table, params_).run();
      },
      tables_);
}

}  // namespace cgdem
