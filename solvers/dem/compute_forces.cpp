// Force pass of the DEM step: contacts with neighbours and walls, gravity, external force.
//   reads  x, v, omega, radius, species, f_ext, neighbour lists, wall frame
//   writes force, torque, contact histories (xi), per-particle energy accounts
// Pass 1 (per block of owners): a screening loop finds the active entries (pairs in
// contact, or whose contact has just ended); their histories are copied to a block
// buffer, evaluated in one loop that the compiler vectorizes (pair_kernel below) and
// copied back. Every other entry would give zero shares and keep its empty history, so it
// is skipped. The owner sums its shares in entry order. The partner's shares are summed
// in entry order too: directly, when one thread evaluates all of that partner's entries
// (every particle on 1 thread; all but those near a chunk boundary on several), or else
// stored at the entry's place in the reverse index and summed in pass 2 (per particle).
// No shared writes and every sum in a fixed order, so the result is the same for any
// number of threads (and the same bits as evaluating every entry into pass 2).
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

namespace cgdem {

namespace {

// Field by field (plain loads and stores vectorize, aggregate copies do not).
inline Vec3 load(const Vec3& a) { return {a.x, a.y, a.z}; }
inline void store(Vec3& a, const Vec3& b) { a.x = b.x, a.y = b.y, a.z = b.z; }
inline contact::History load(const contact::History& h) {
  return {load(h.xi), load(h.ft), h.vn, h.ftvt};
}
inline void store(contact::History& h, const contact::History& b) {
  store(h.xi, b.xi), store(h.ft, b.ft), h.vn = b.vn, h.ftvt = b.ftvt;
}
using contact::select;

// What the pair kernel reads, as plain arrays.
struct PairArrays {
  const Vec3 *x, *v, *w;
  const double* radius;
  const int* partner;
};

// Per-block buffers of the active entries k = 0..na-1 (entry ent[k], owner own[k]).
struct ActiveEntries {
  const int *ent, *own;
  const double *sx, *sy, *sz;  // the partner's periodic image shift
  contact::History* hist;      // read and written: a copy of the entry's history
  Vec3 *f_partner, *t_partner;  // written: force on the partner, n x F_t
  double *damp, *fric;          // written: energy dissipated in this step
  int* touching;                // written: 1 when the pair overlaps
};

// Active entries k = 0..na-1: per entry, the contact force (eqs. 6-7) or, for a pair that
// has just separated, the end of its contact; writes the partner's share, the updated
// history and the energy dissipated. `params(i, j)` gives the contact parameters. Every
// lane computes exactly what the scalar contact law computes (IEEE operations only, no
// contraction), so the vector width does not change the result.
template <class ParamsOf>
inline __attribute__((always_inline)) void pair_entries(const PairArrays& a, const ActiveEntries& b, int na, double dt,
                                                        ParamsOf params) {
  const Vec3* __restrict x = a.x;
  const Vec3* __restrict v = a.v;
  const Vec3* __restrict w = a.w;
  const double* __restrict radius = a.radius;
  const int* __restrict partner = a.partner;
  const int* __restrict ent = b.ent;
  const int* __restrict owner = b.own;
  const double* __restrict sx = b.sx;
  const double* __restrict sy = b.sy;
  const double* __restrict sz = b.sz;
  contact::History* __restrict hist = b.hist;
  Vec3* __restrict f_partner = b.f_partner;
  Vec3* __restrict t_partner = b.t_partner;
  double* __restrict damp = b.damp;
  double* __restrict fric = b.fric;
  int* __restrict touch = b.touching;
#pragma GCC ivdep
  for (int k = 0; k < na; ++k) {
    const int i = owner[k], j = partner[ent[k]];
    const Vec3 d = load(x[i]) - (load(x[j]) + Vec3{sx[k], sy[k], sz[k]});
    const double ri = radius[i], rj = radius[j];
    const double rsum = ri + rj;
    const double dist2 = norm2(d);
    const bool touching = dist2 < rsum * rsum;
    const contact::History h0 = load(hist[k]);
    const bool ended = !touching & !h0.empty();  // out of contact: the history ends
    const double dist = cgdem_sqrt(dist2);
    const Vec3 nrm = (1.0 / dist) * d;  // from j to i
    // Velocity of i's contact point relative to j's.
    const Vec3 v_rel = (load(v[i]) - load(v[j])) - cross(ri * load(w[i]) + rj * load(w[j]), nrm);
    const contact::Params c = params(i, j);
    contact::History h = load(h0), h_end = load(h0);
    Vec3 f_t;
    contact::Work wc, we;
    const Vec3 fc = contact::force(c, nrm, rsum - dist, v_rel, h, dt, f_t, wc);
    contact::finish(c, nrm, v_rel, h_end, dt, we);  // books the rest of the last step's work
    const Vec3 nxt = cross(nrm, f_t);
    store(f_partner[k], select(touching, -fc, Vec3{}));
    store(t_partner[k], select(touching, nxt, Vec3{}));  // the partner's torque is (r_j n) x (-F_t) = -r_j n x F_t
    damp[k] = select(touching, wc.damping_n, select(ended, we.damping_n, 0.0));
    fric[k] = select(touching, wc.friction, select(ended, we.friction, 0.0));
    touch[k] = touching;
    // New history: the updated one, cleared (ended) or unchanged (no contact).
    store(hist[k], {select(touching, h.xi, select(ended, h_end.xi, h0.xi)),
                    select(touching, h.ft, select(ended, h_end.ft, h0.ft)),
                    select(touching, h.vn, select(ended, h_end.vn, h0.vn)),
                    select(touching, h.ftvt, select(ended, h_end.ftvt, h0.ftvt))});
  }
}

// The kernel, built for AVX-512 and AVX2 as well as the baseline (the loader picks the
// widest the processor has): one species (parameters in registers) or several.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_one_species(
    const PairArrays& a, const ActiveEntries& b, int na, double dt, contact::Params c) {
  pair_entries(a, b, na, dt, [c](int, int) { return c; });
}
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_species(
    const PairArrays& a, const ActiveEntries& b, int na, double dt, const ContactTable& table, const int* species) {
  pair_entries(a, b, na, dt, [&table, species](int i, int j) { return table.pair(species[i], species[j]); });
}

// Which entries e0..e1-1 (owner[e - e0]) need the kernel: those in contact now (the same
// test as the kernel's, same operations) or with a live history (in contact at the last
// evaluation; the kernel then ends the contact). For every other entry the kernel would
// write zero shares and leave the (empty) history alone, so skipping it changes nothing.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void screen_entries(
    const PairArrays& a, int e0, int e1, const int* __restrict owner, const double* const* shift,
    const uint8_t* __restrict live, int* __restrict active) {
  const Vec3* __restrict x = a.x;
  const double* __restrict radius = a.radius;
  const int* __restrict partner = a.partner;
  const double* __restrict sx = shift[0];
  const double* __restrict sy = shift[1];
  const double* __restrict sz = shift[2];
#pragma GCC ivdep
  for (int e = e0; e < e1; ++e) {
    const int i = owner[e - e0], j = partner[e];
    const Vec3 d = load(x[i]) - (load(x[j]) + Vec3{sx[e - e0], sy[e - e0], sz[e - e0]});
    const double rsum = radius[i] + radius[j];
    active[e - e0] = (norm2(d) < rsum * rsum) | (live[e] != 0);
  }
}

constexpr int kBlock = 128;  // owners per block of the pair pass

}  // namespace

void DemSolver::compute_forces() {
  auto scope = timers_.scope(t_force_);
  const int n = static_cast<int>(p_.size());
  const double dt = params_.dt;
  const Vec3 g = params_.gravity;
  Particles& p = p_;
  NeighborList& nl = nl_;
  const ContactTable& table = table_;
  const geometry::Scene::Frame& frame = frame_;
  const PairArrays arrays{p.x.data(), p.v.data(), p.omega.data(), p.radius.data(), nl.partner.data()};
  const int nblocks = (n + kBlock - 1) / kBlock;
  // Plain pointers for the scalar loops (vector members would be reloaded after each store).
  const int *offset = nl.offset.data(), *wall_offset = nl.wall_offset.data();
  const int *rev_offset = nl.rev_offset.data(), *rev_pos = nl.rev_pos.data();
  Vec3 *f_share = nl.f_partner.data(), *t_share = nl.t_partner.data();
  Vec3 *f_acc = nl.f_acc.data(), *t_acc = nl.t_acc.data();
  const int* partner = nl.partner.data();
  contact::History* hist = nl.hist.data();
  uint8_t* live = nl.live.data();
  const Vec3 *x = p.x.data(), *v = p.v.data(), *omega = p.omega.data(), *f_ext = p.f_ext.data();
  const double *radius = p.radius.data(), *inv_mass = p.inv_mass.data();
  Vec3 *force = p.force.data(), *torque_out = p.torque.data();
  double *e_damping = p.e_damping.data(), *e_friction = p.e_friction.data(), *w_walls = p.w_walls.data();
  const bool periodic = nl.periodic.any();
  const int n_owned = static_cast<int>(nl.owned(p));  // n without ghosts
  const int64_t* id = p.id.data();

#pragma omp parallel if (n >= 512)
  {
    // Thread `tid` evaluates the blocks chunk(tid) .. chunk(tid + 1) - 1, owners in order.
    const int team = omp_get_num_threads(), tid = omp_get_thread_num();
    auto chunk = [nblocks, team](int t) { return static_cast<int>(static_cast<long>(nblocks) * t / team); };
#pragma omp single
    if (nl.direct_team != team) {
      // Particle j is direct when its lowest and highest owners (hence all of them) are in
      // one thread's chunk: that thread then adds j's shares in entry order into f_acc,
      // which is the sum pass 2 would form. The stored shares are cleared (an entry whose
      // partner changes kind must not leave an old share behind).
      std::vector<int> chunk_of(nblocks);
      for (int t = 0; t < team; ++t)
        for (int b = chunk(t); b < chunk(t + 1); ++b) chunk_of[b] = t;
      nl.direct.resize(n);
      for (int j = 0; j < n; ++j)
        nl.direct[j] = nl.first_owner[j] < 0 ||
                       chunk_of[nl.first_owner[j] / kBlock] == chunk_of[nl.last_owner[j] / kBlock];
      std::fill(nl.f_partner.begin(), nl.f_partner.end(), Vec3{});
      std::fill(nl.t_partner.begin(), nl.t_partner.end(), Vec3{});
      nl.direct_team = team;
    }  // (implicit barrier)
    const uint8_t* direct = nl.direct.data();
    // Per-block buffers (grown, never shrunk): entries of the block (index e - e0), then
    // its active entries (index k).
    std::vector<int> owner, starts, active, ent, own, touching, kstart;
    std::vector<double> shift[3], ashift[3], zero;
    std::vector<double> damp, fric;
    std::vector<contact::History> h;
    std::vector<Vec3> fp, tp;
    kstart.resize(kBlock + 1);
    for (int b = chunk(tid); b < chunk(tid + 1); ++b) {
      const int i0 = b * kBlock, i1 = std::min(n, i0 + kBlock);
      const int e0 = offset[i0], e1 = offset[i1], ne = e1 - e0;
      if (starts.size() < static_cast<size_t>(ne) + 1) {
        starts.resize(ne + 1);
        for (auto* vec : {&owner, &active, &ent, &own, &touching}) vec->resize(ne);
        zero.resize(ne);  // stays 0
        damp.resize(ne);
        fric.resize(ne);
        h.resize(ne);
        fp.resize(ne);
        tp.resize(ne);
        if (periodic)
          for (int k = 0; k < 3; ++k) shift[k].resize(ne), ashift[k].resize(ne);
      }
      // Owner of each entry, without branches: count the owners that start at each entry.
      std::fill(starts.begin(), starts.begin() + ne + 1, 0);
      for (int i = i0 + 1; i < i1; ++i) ++starts[offset[i] - e0];
      for (int e = 0, i = i0; e < ne; ++e) owner[e] = i += starts[e];
      const double* shift_k[3] = {zero.data(), zero.data(), zero.data()};
      const double* ashift_k[3] = {zero.data(), zero.data(), zero.data()};
      if (periodic) {
        for (int e = e0; e < e1; ++e)
          for (int k = 0; k < 3; ++k) shift[k][e - e0] = nl.shift[nl.image[e]][k];
        for (int k = 0; k < 3; ++k) shift_k[k] = shift[k].data(), ashift_k[k] = ashift[k].data();
      }

      // The active entries, in entry order, with a copy of their history (whole records:
      // cheaper than the kernel gathering them lane by lane).
      screen_entries(arrays, e0, e1, owner.data(), shift_k, live, active.data());
      int na = 0;
      for (int e = 0; e < ne; ++e) {
        ent[na] = e + e0;
        own[na] = owner[e];
        na += active[e];
      }
      std::fill(kstart.begin(), kstart.begin() + (i1 - i0) + 1, 0);
      for (int k = 0; k < na; ++k) {
        h[k] = hist[ent[k]];
        ++kstart[own[k] - i0 + 1];
      }
      for (int i = 0; i < i1 - i0; ++i) kstart[i + 1] += kstart[i];
      if (periodic)
        for (int k = 0; k < na; ++k)
          for (int c = 0; c < 3; ++c) ashift[c][k] = shift[c][ent[k] - e0];
      const ActiveEntries act{ent.data(), own.data(), ashift_k[0], ashift_k[1], ashift_k[2], h.data(),
                              fp.data(),  tp.data(),  damp.data(),  fric.data(),  touching.data()};
      if (table.species_count() == 1)
        pair_kernel_one_species(arrays, act, na, dt, table.pair(0, 0));
      else
        pair_kernel_species(arrays, act, na, dt, table, p.species.data());
      if (n_owned < n)  // the ghost's rank books a split pair whose lower id is its parcel
        for (int k = 0; k < na; ++k) {
          const int j = partner[ent[k]];
          if (j >= n_owned && id[j] < id[own[k]]) damp[k] = fric[k] = 0;
        }
      // Back to the lists: history, liveness, and the partner's share: summed directly
      // (this thread evaluates all of the partner's entries, in entry order) or stored at
      // its place in the reverse index for pass 2. Skipped entries add +0, which changes
      // no sum that starts at +0.
      for (int k = 0; k < na; ++k) {
        const int e = ent[k], j = partner[e];
        hist[e] = h[k];
        live[e] = static_cast<uint8_t>(touching[k]);
        if (direct[j]) {
          f_acc[j] += fp[k];
          t_acc[j] += tp[k];
        } else {
          f_share[rev_pos[e]] = fp[k];
          t_share[rev_pos[e]] = tp[k];
        }
      }

      for (int i = i0; i < i1; ++i) {
        const double ri = radius[i];
        Vec3 f = (1.0 / inv_mass[i]) * g + f_ext[i];
        Vec3 torque{};
        double e_damp = 0, e_fric = 0, w_wall = 0;

        // The owner's shares, in entry order (the skipped entries' shares are zero).
        for (int k = kstart[i - i0]; k < kstart[i - i0 + 1]; ++k) {
          f -= fp[k];
          torque -= ri * tp[k];  // (-r_i n) x F_t
          e_damp += damp[k];
          e_fric += fric[k];
        }

        const Vec3 xi = x[i], vi = v[i], wi = omega[i];
        const int si = p.species[i];
        for (int e = wall_offset[i]; e < wall_offset[i + 1]; ++e) {
          const int part = nl.wall_part[e];
          Vec3 grad;
          const double s = frame.part_distance(part, xi, grad);  // eq. (15): phi, grad phi
          if (s >= ri && nl.wall_hist[e].empty()) continue;
          const double gl = norm(grad);
          const Vec3 nrm = (1.0 / gl) * grad;
          const Vec3 u_wall = frame.part_velocity(part);
          const Vec3 v_rel = (vi - u_wall) - cross(ri * wi, nrm);
          if (s >= ri) {  // the contact has just ended
            contact::Work w;
            contact::finish(table.wall(si), nrm, v_rel, nl.wall_hist[e], dt, w);
            e_damp += w.damping_n;
            e_fric += w.friction;
            continue;
          }
          // eq. (16)-(17): overlap (d/2 - phi) along grad phi, scaled by |grad phi| (= 1 for exact SDFs)
          const double delta = (ri - s) * gl;
          Vec3 f_t;
          contact::Work w;
          const Vec3 fc = contact::force(table.wall(si), nrm, delta, v_rel, nl.wall_hist[e], dt, f_t, w);
          f += fc;
          torque += cross(-ri * nrm, f_t);
          e_damp += w.damping_n;
          e_fric += w.friction;
          w_wall += dot(fc, u_wall) * dt;  // power of the contact force at the wall's velocity
        }

        force[i] = f;
        torque_out[i] = torque;
        e_damping[i] += e_damp;
        e_friction[i] += e_fric;
        w_walls[i] += w_wall;
      }
    }

    // Pass 2: the partners' shares, in increasing entry order (summed already, or stored
    // in that order).
#pragma omp barrier
#pragma omp for schedule(static)
    for (int j = 0; j < n; ++j) {
      Vec3 f{}, t{};
      if (direct[j]) {
        f = f_acc[j], t = t_acc[j];
        f_acc[j] = Vec3{}, t_acc[j] = Vec3{};
      } else {
        for (int k = rev_offset[j]; k < rev_offset[j + 1]; ++k) {
          f += f_share[k];
          t += t_share[k];
        }
      }
      force[j] += f;
      torque_out[j] -= radius[j] * t;
    }
  }
}

}  // namespace cgdem
