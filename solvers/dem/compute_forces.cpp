// Force pass of the DEM step: contacts with neighbours and walls, gravity, external force.
//   reads  x, v, omega, radius, species, f_ext, neighbour lists, wall frame
//   writes force, torque, contact histories (xi), per-particle energy accounts
// Pass 1 (per block of owners): every listed pair is evaluated once, in a loop over the
// block's entries that the compiler vectorizes (pair_kernel below); the partner's share
// is stored with the entry and the owner sums its shares in entry order. Pass 2 (per
// particle): the stored shares are gathered through the reverse index. No shared writes
// and every sum in a fixed order, so the result is the same for any number of threads.
// The energy a pair dissipates is booked to its owner.
// No floating-point contraction (the AVX2/AVX-512 builds of the kernel would otherwise
// fuse multiply-adds): every build computes the same bits as the baseline one.
#pragma GCC optimize("fp-contract=off")
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

// What the pair kernel reads and writes, as plain arrays.
struct PairArrays {
  const Vec3 *x, *v, *w;
  const double* radius;
  const int* partner;
  contact::History* hist;  // read and written
  Vec3 *f_partner, *t_partner;  // written: force on the partner, n x F_t
};

// Entries e0..e1-1 (owner[e - e0] owns entry e, shift[k][e - e0] is component k of its
// partner's periodic image shift): per entry, the contact force (eqs. 6-7) or, for a pair
// that has just separated, the end of its contact; writes the partner's share, the updated
// history and the energy dissipated (damp, fric; index e - e0). `params(i, j)` gives the
// contact parameters. Every lane computes exactly what the scalar contact law computes
// (IEEE operations only, no contraction), so the vector width does not change the result.
template <class ParamsOf>
inline __attribute__((always_inline)) void pair_entries(const PairArrays& a, int e0, int e1,
                                                        const int* __restrict owner, const double* const* shift,
                                                        double dt, double* __restrict damp, double* __restrict fric,
                                                        ParamsOf params) {
  const Vec3* __restrict x = a.x;
  const Vec3* __restrict v = a.v;
  const Vec3* __restrict w = a.w;
  contact::History* __restrict hist = a.hist;
  Vec3* __restrict f_partner = a.f_partner;
  Vec3* __restrict t_partner = a.t_partner;
  const double* __restrict radius = a.radius;
  const int* __restrict partner = a.partner;
  const double* __restrict sx = shift[0];
  const double* __restrict sy = shift[1];
  const double* __restrict sz = shift[2];
#pragma GCC ivdep
  for (int e = e0; e < e1; ++e) {
    const int i = owner[e - e0], j = partner[e];
    const Vec3 d = load(x[i]) - (load(x[j]) + Vec3{sx[e - e0], sy[e - e0], sz[e - e0]});
    const double ri = radius[i], rj = radius[j];
    const double rsum = ri + rj;
    const double dist2 = norm2(d);
    const bool touching = dist2 < rsum * rsum;
    const contact::History h0 = load(hist[e]);
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
    store(f_partner[e], select(touching, -fc, Vec3{}));
    store(t_partner[e], select(touching, nxt, Vec3{}));  // the partner's torque is (r_j n) x (-F_t) = -r_j n x F_t
    damp[e - e0] = select(touching, wc.damping_n, select(ended, we.damping_n, 0.0));
    fric[e - e0] = select(touching, wc.friction, select(ended, we.friction, 0.0));
    // New history: the updated one, cleared (ended) or unchanged (no contact).
    store(hist[e], {select(touching, h.xi, select(ended, h_end.xi, h0.xi)),
                    select(touching, h.ft, select(ended, h_end.ft, h0.ft)),
                    select(touching, h.vn, select(ended, h_end.vn, h0.vn)),
                    select(touching, h.ftvt, select(ended, h_end.ftvt, h0.ftvt))});
  }
}

// The kernel, built for AVX-512 and AVX2 as well as the baseline (the loader picks the
// widest the processor has): one species (parameters in registers) or several.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_one_species(
    const PairArrays& a, int e0, int e1, const int* owner, const double* const* shift, double dt, double* damp,
    double* fric, contact::Params c) {
  pair_entries(a, e0, e1, owner, shift, dt, damp, fric, [c](int, int) { return c; });
}
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_kernel_species(
    const PairArrays& a, int e0, int e1, const int* owner, const double* const* shift, double dt, double* damp,
    double* fric, const ContactTable& table, const int* species) {
  pair_entries(a, e0, e1, owner, shift, dt, damp, fric,
               [&table, species](int i, int j) { return table.pair(species[i], species[j]); });
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
  const PairArrays arrays{p.x.data(),       p.v.data(),        p.omega.data(),  p.radius.data(),
                          nl.partner.data(),          nl.hist.data(),
                          nl.f_partner.data(), nl.t_partner.data()};
  const int nblocks = (n + kBlock - 1) / kBlock;
  // Plain pointers for the scalar loops (vector members would be reloaded after each store).
  const int *offset = nl.offset.data(), *wall_offset = nl.wall_offset.data();
  const int *rev_offset = nl.rev_offset.data(), *rev_entry = nl.rev_entry.data();
  const Vec3 *f_partner = nl.f_partner.data(), *t_partner = nl.t_partner.data();
  const Vec3 *x = p.x.data(), *v = p.v.data(), *omega = p.omega.data(), *f_ext = p.f_ext.data();
  const double *radius = p.radius.data(), *inv_mass = p.inv_mass.data();
  Vec3 *force = p.force.data(), *torque_out = p.torque.data();
  double *e_damping = p.e_damping.data(), *e_friction = p.e_friction.data(), *w_walls = p.w_walls.data();
  const bool periodic = nl.periodic.any();

#pragma omp parallel if (n >= 512)
  {
    std::vector<int> owner, starts;
    std::vector<double> shift[3], zero;
    std::vector<double> damp, fric;
#pragma omp for schedule(static)
    for (int b = 0; b < nblocks; ++b) {
      const int i0 = b * kBlock, i1 = std::min(n, i0 + kBlock);
      const int e0 = offset[i0], e1 = offset[i1], ne = e1 - e0;
      if (starts.size() < static_cast<size_t>(ne) + 1) {  // grown, never shrunk
        starts.resize(ne + 1);
        owner.resize(ne);
        zero.resize(ne);  // stays 0
        damp.resize(ne);
        fric.resize(ne);
        if (periodic)
          for (auto& s : shift) s.resize(ne);
      }
      // Owner of each entry, without branches: count the owners that start at each entry.
      std::fill(starts.begin(), starts.begin() + ne + 1, 0);
      for (int i = i0 + 1; i < i1; ++i) ++starts[offset[i] - e0];
      for (int e = 0, i = i0; e < ne; ++e) owner[e] = i += starts[e];
      const double* shift_k[3] = {zero.data(), zero.data(), zero.data()};
      if (periodic) {
        for (int e = e0; e < e1; ++e)
          for (int k = 0; k < 3; ++k) shift[k][e - e0] = nl.shift[nl.image[e]][k];
        for (int k = 0; k < 3; ++k) shift_k[k] = shift[k].data();
      }
      if (table.species_count() == 1)
        pair_kernel_one_species(arrays, e0, e1, owner.data(), shift_k, dt, damp.data(), fric.data(), table.pair(0, 0));
      else
        pair_kernel_species(arrays, e0, e1, owner.data(), shift_k, dt, damp.data(), fric.data(), table,
                            p.species.data());

      for (int i = i0; i < i1; ++i) {
        const double ri = radius[i];
        Vec3 f = (1.0 / inv_mass[i]) * g + f_ext[i];
        Vec3 torque{};
        double e_damp = 0, e_fric = 0, w_wall = 0;

        // The owner's shares, in entry order (zero for pairs out of contact).
        for (int e = offset[i]; e < offset[i + 1]; ++e) {
          f -= f_partner[e];
          torque -= ri * t_partner[e];  // (-r_i n) x F_t
          e_damp += damp[e - e0];
          e_fric += fric[e - e0];
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

    // Pass 2: the partners' shares, in increasing entry order.
#pragma omp for schedule(static)
    for (int j = 0; j < n; ++j) {
      Vec3 f{}, t{};
      for (int k = rev_offset[j]; k < rev_offset[j + 1]; ++k) {
        const int e = rev_entry[k];
        f += f_partner[e];
        t += t_partner[e];
      }
      force[j] += f;
      torque_out[j] -= radius[j] * t;
    }
  }
}

}  // namespace cgdem
