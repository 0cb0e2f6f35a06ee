// The vectorized loops of the force pass (compute_forces.cpp, the only includer): the
// screening of list entries and the pair kernel, for any contact law of the registry
// (contact/laws.hpp). Each is built for AVX-512 and AVX2 as well as the baseline (the
// loader picks the widest the processor has); every lane computes exactly what the scalar
// code computes (IEEE operations only, no contraction: the includer turns it off), so the
// vector width does not change the result.
#pragma once
#include <cstdint>

#include "contact/history.hpp"
#include "contact/law_table.hpp"

namespace cgdem::forces {

// Field by field (plain loads and stores vectorize, aggregate copies do not).
inline Vec3 load(const Vec3& a) { return {a.x, a.y, a.z}; }
inline void store(Vec3& a, const Vec3& b) { a.x = b.x, a.y = b.y, a.z = b.z; }
inline contact::History load(const contact::History& h) { return {load(h.xi), load(h.ft), h.s1, h.s2}; }
inline void store(contact::History& h, const contact::History& b) {
  store(h.xi, b.xi), store(h.ft, b.ft), h.s1 = b.s1, h.s2 = b.s2;
}
// Slot by slot: c ? a : b.
inline contact::History select(bool c, const contact::History& a, const contact::History& b) {
  return {contact::select(c, a.xi, b.xi), contact::select(c, a.ft, b.ft), contact::select(c, a.s1, b.s1),
          contact::select(c, a.s2, b.s2)};
}

// What the kernels read, as plain arrays.
struct PairArrays {
  const Vec3 *x, *v, *w;
  const double* radius;
  const int* partner;
};

// Per-block buffers of the active entries k = 0..na-1 (entry ent[k], owner own[k]).
struct ActiveEntries {
  const int *ent, *own;
  const double *sx, *sy, *sz;   // the partner's periodic image shift
  contact::History* hist;       // read and written: a copy of the entry's history (with the accounts)
  Vec3* xi;                     // read and written: a copy of its spring (without them)
  Vec3 *f_partner, *t_partner;  // written: force on the partner, n x F_t
  double *damp, *fric;          // written: energy dissipated in this step (with the accounts)
  int* touching;                // written: 1 when the pair overlaps
};

// Active entries k = 0..na-1: per entry, the contact force of Law or, for a pair that has
// just separated, the end of its contact (Law::finish); writes the partner's share, the
// updated history and the energy dissipated. `params(i, j)` gives the contact parameters.
// Without the Accounts only the spring xi is read and written (the force depends on it
// alone, laws.hpp): the same forces and springs, no Law::finish, no energies.
template <class Law, bool Accounts, class ParamsOf>
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
  Vec3* __restrict spring = b.xi;
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
    const contact::History h0 = Accounts ? load(hist[k]) : contact::History{load(spring[k]), Vec3{}, 0, 0};
    const double dist = cgdem_sqrt(dist2);
    const Vec3 nrm = (1.0 / dist) * d;  // from j to i
    // Velocity of i's contact point relative to j's.
    const Vec3 v_rel = (load(v[i]) - load(v[j])) - cross(ri * load(w[i]) + rj * load(w[j]), nrm);
    const typename Law::Params c = params(i, j);
    typename Law::History h = Law::unpack(h0);
    Vec3 f_t;
    contact::Work wc;
    const Vec3 fc = Law::force(c, nrm, rsum - dist, v_rel, h, dt, f_t, wc);
    const Vec3 nxt = cross(nrm, f_t);
    store(f_partner[k], contact::select(touching, -fc, Vec3{}));
    // The partner's torque is (r_j n) x (-F_t) = -r_j n x F_t.
    store(t_partner[k], contact::select(touching, nxt, Vec3{}));
    touch[k] = touching;
    if constexpr (Accounts) {
      const bool ended = !touching & !h0.empty();  // out of contact: the history ends
      typename Law::History h_end = Law::unpack(h0);
      contact::Work we;
      Law::finish(c, nrm, v_rel, h_end, dt, we);  // books the rest of the last step's work
      damp[k] = contact::select(touching, wc.damping_n, contact::select(ended, we.damping_n, 0.0));
      fric[k] = contact::select(touching, wc.friction, contact::select(ended, we.friction, 0.0));
      // New history: the updated one, cleared (ended) or unchanged (no contact).
      store(hist[k], select(touching, Law::pack(h), select(ended, Law::pack(h_end), h0)));
    } else {
      // The updated spring, or none (an ended contact's is cleared; no contact had none).
      store(spring[k], contact::select(touching, Law::pack(h).xi, Vec3{}));
    }
  }
}

// The kernel: one species (parameters in registers) or several.
template <class Law, bool Accounts>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_one_species(
    const PairArrays& a, const ActiveEntries& b, int na, double dt, typename Law::Params c) {
  pair_entries<Law, Accounts>(a, b, na, dt, [c](int, int) { return c; });
}
template <class Law, bool Accounts>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_species(
    const PairArrays& a, const ActiveEntries& b, int na, double dt, const contact::LawTable<Law>& table,
    const int* species) {
  pair_entries<Law, Accounts>(a, b, na, dt,
                              [&table, species](int i, int j) { return table.pair(species[i], species[j]); });
}

// Which entries e0..e1-1 (owner[e - e0]) need the kernel: those in contact now (the same
// test as the kernel's, same operations) or with a live history (in contact at the last
// evaluation; the kernel then ends the contact). For every other entry the kernel would
// write zero shares and leave the (empty) history alone, so skipping it changes nothing.
// Independent of the law. With Uniform, every particle's radius is r and rsum_uniform is
// r + r, the sum the loop would form: the radii need not be gathered.
template <bool Uniform>
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) inline void screen_entries(
    const PairArrays& a, int e0, int e1, const int* __restrict owner, const double* const* shift,
    const uint8_t* __restrict live, int* __restrict active, double rsum_uniform) {
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
    const double rsum = Uniform ? rsum_uniform : radius[i] + radius[j];
    active[e - e0] = (norm2(d) < rsum * rsum) | (live[e] != 0);
  }
}

}  // namespace cgdem::forces
