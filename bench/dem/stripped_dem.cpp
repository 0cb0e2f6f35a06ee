// The stripped reference step (stripped_dem.hpp). Built with -fno-math-errno, a 512-bit
// vector preference and Intel tuning (hardware gathers; bench/CMakeLists.txt), with fused
// multiply-adds allowed, so that GCC vectorizes the pair and wall loops as far as it can:
// the point is the fastest plain C++ form of the law, not reproducible bits.
#pragma GCC optimize("fp-contract=fast")
#include "bench/dem/stripped_dem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace cgdem::bench {

namespace {

constexpr int kBlock = 256;  // owners per block of the force pass

// The particle fields the contacts read (structure of arrays: 9 arrays).
struct State {
  const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz;
};

// One contact's history: the tangential spring xi, and with the energy accounts the last
// step's tangential force, normal velocity and ft . v_t (contact/linear_law.hpp).
struct Hist {
  double xi[3], ft[3], vn, ftvt;
};

// The contact law for one entry, without branches (a loop of it vectorizes): from the unit
// normal n (partner to this particle), the overlap, the relative velocity u of the contact
// point and the history h (updated: cleared when `touching` is false), the force on this
// particle f and n x F_t (m), zero out of contact. With the accounts, also the energy
// dissipated by the normal dashpot and tangentially in this step
// (contact::LinearSpringDashpot::force, and ::finish for a contact that has just ended),
// as the engine books it.
struct Law {
  double k, eta, mu, inv_k, dt;
  template <bool kAccounts>
  inline __attribute__((always_inline)) void apply(bool touching, double nx, double ny, double nz, double overlap,
                                                   double ux, double uy, double uz, Hist& h, double f[3],
                                                   double m[3], double& damp, double& fric) const {
    const double vn = ux * nx + uy * ny + uz * nz;
    const double tx = ux - vn * nx, ty = uy - vn * ny, tz = uz - vn * nz;
    const double fn = k * overlap - eta * vn;
    // History into the tangent plane with its length kept, then integrated.
    const double len2 = h.xi[0] * h.xi[0] + h.xi[1] * h.xi[1] + h.xi[2] * h.xi[2];
    const double hn = h.xi[0] * nx + h.xi[1] * ny + h.xi[2] * nz;
    const double plen2 = len2 - hn * hn;
    const double scale = plen2 > 0 ? std::sqrt(len2 / plen2) : 1.0;
    double hx = (h.xi[0] - hn * nx) * scale + dt * tx;
    double hy = (h.xi[1] - hn * ny) * scale + dt * ty;
    double hz = (h.xi[2] - hn * nz) * scale + dt * tz;
    double ftx = -(k * hx + eta * tx), fty = -(k * hy + eta * ty), ftz = -(k * hz + eta * tz);
    const double ft2 = ftx * ftx + fty * fty + ftz * ftz, limit = mu * std::fabs(fn);
    const bool sliding = ft2 > limit * limit;
    const double cut = sliding ? limit / std::sqrt(ft2) : 1.0;
    ftx *= cut, fty *= cut, ftz *= cut;
    if (sliding) hx = -(ftx + eta * tx) * inv_k, hy = -(fty + eta * ty) * inv_k, hz = -(ftz + eta * tz) * inv_k;
    f[0] = touching ? fn * nx + ftx : 0.0, f[1] = touching ? fn * ny + fty : 0.0, f[2] = touching ? fn * nz + ftz : 0.0;
    m[0] = touching ? ny * ftz - nz * fty : 0.0, m[1] = touching ? nz * ftx - nx * ftz : 0.0;
    m[2] = touching ? nx * fty - ny * ftx : 0.0;
    if constexpr (kAccounts) {
      const double ftvt = ftx * tx + fty * ty + ftz * tz;
      const double back = 0.5 * dt * ((h.ft[0] * tx + h.ft[1] * ty + h.ft[2] * tz) - h.ftvt);
      const double half_old = 0.5 * dt * (eta * h.vn) * (vn - h.vn);
      const double spring_old = 0.5 * k * len2, spring_new = 0.5 * k * (hx * hx + hy * hy + hz * hz);
      damp = touching ? (eta * vn) * vn * dt + half_old : half_old;
      fric = touching ? -ftvt * dt - (spring_new - spring_old) - back : spring_old - back;
      h.ft[0] = touching ? ftx : 0.0, h.ft[1] = touching ? fty : 0.0, h.ft[2] = touching ? ftz : 0.0;
      h.vn = touching ? vn : 0.0;
      h.ftvt = touching ? ftvt : 0.0;
    }
    h.xi[0] = touching ? hx : 0.0, h.xi[1] = touching ? hy : 0.0, h.xi[2] = touching ? hz : 0.0;
  }
};

Law law_of(const contact::Params& c, double dt) {
  return {c.l3 * c.k, c.l3 * c.eta, c.mu, 1.0 / (c.l3 * c.k), dt};
}

// History arrays (structure of arrays, indexed by entry or wall candidate): xi, and with
// the accounts ft, vn, ftvt.
struct HistArrays {
  double *xi[3], *ft[3], *vn, *ftvt;
};

template <bool kAccounts>
inline Hist load(const HistArrays& a, int e) {
  Hist h{{a.xi[0][e], a.xi[1][e], a.xi[2][e]}, {0, 0, 0}, 0, 0};
  if constexpr (kAccounts) h.ft[0] = a.ft[0][e], h.ft[1] = a.ft[1][e], h.ft[2] = a.ft[2][e], h.vn = a.vn[e], h.ftvt = a.ftvt[e];
  return h;
}
template <bool kAccounts>
inline void store(const HistArrays& a, int e, const Hist& h) {
  a.xi[0][e] = h.xi[0], a.xi[1][e] = h.xi[1], a.xi[2][e] = h.xi[2];
  if constexpr (kAccounts) a.ft[0][e] = h.ft[0], a.ft[1][e] = h.ft[1], a.ft[2][e] = h.ft[2], a.vn[e] = h.vn, a.ftvt[e] = h.ftvt;
}

// Force, a torque term and the two dissipated energies: per entry of a block, what the
// pair loop writes (force on the owner, n x F_t, energies); per particle, the sums the
// wall loop adds to (force, torque, energies).
struct Terms {
  double *fx, *fy, *fz, *tx, *ty, *tz, *damp, *fric;
};

// Entries 0..ne-1 (owner own[e], partner part[e], history h[e]).
template <bool kAccounts>
inline __attribute__((always_inline)) void pair_entries(const State& s, const int* __restrict own,
                                                        const int* __restrict part, const HistArrays& h,
                                                        const Terms& out, int ne, double r, Law law) {
  const double *__restrict x = s.x, *__restrict y = s.y, *__restrict z = s.z;
  const double *__restrict vx = s.vx, *__restrict vy = s.vy, *__restrict vz = s.vz;
  const double *__restrict wx = s.wx, *__restrict wy = s.wy, *__restrict wz = s.wz;
  double *__restrict fx = out.fx, *__restrict fy = out.fy, *__restrict fz = out.fz;
  double *__restrict mx = out.tx, *__restrict my = out.ty, *__restrict mz = out.tz;
  double *__restrict damp = out.damp, *__restrict fric = out.fric;
  const double d = 2 * r;
#pragma GCC ivdep
  for (int e = 0; e < ne; ++e) {
    const int i = own[e], j = part[e];
    const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
    const double dist2 = dx * dx + dy * dy + dz * dz;
    const double dist = std::sqrt(dist2), inv = 1.0 / dist;
    const double nx = dx * inv, ny = dy * inv, nz = dz * inv;
    const double ax = r * (wx[i] + wx[j]), ay = r * (wy[i] + wy[j]), az = r * (wz[i] + wz[j]);
    const double ux = vx[i] - vx[j] - (ay * nz - az * ny);
    const double uy = vy[i] - vy[j] - (az * nx - ax * nz);
    const double uz = vz[i] - vz[j] - (ax * ny - ay * nx);
    Hist c = load<kAccounts>(h, e);
    double f[3], m[3], de = 0, fe = 0;
    law.apply<kAccounts>(dist2 < d * d, nx, ny, nz, d - dist, ux, uy, uz, c, f, m, de, fe);
    store<kAccounts>(h, e, c);
    fx[e] = f[0], fy[e] = f[1], fz[e] = f[2], mx[e] = m[0], my[e] = m[1], mz[e] = m[2];
    if constexpr (kAccounts) damp[e] = de, fric[e] = fe;
  }
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_loop(
    const State& s, const int* own, const int* part, const HistArrays& h, const Terms& out, int ne, double r,
    Law law) {
  pair_entries<false>(s, own, part, h, out, ne, r, law);
}
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void pair_loop_accounts(
    const State& s, const int* own, const int* part, const HistArrays& h, const Terms& out, int ne, double r,
    Law law) {
  pair_entries<true>(s, own, part, h, out, ne, r, law);
}

// One planar wall against its candidates (distinct particles cand[q], histories h[q]),
// without branches; adds to their force and torque (-r n x F_t) and energy accounts.
template <bool kAccounts>
inline __attribute__((always_inline)) void wall_candidates(const State& s, const Terms& sum, const int* __restrict cand,
                                                           const HistArrays& h, int nc, Plane pl, double r, Law law) {
  const double *__restrict x = s.x, *__restrict y = s.y, *__restrict z = s.z;
  const double *__restrict vx = s.vx, *__restrict vy = s.vy, *__restrict vz = s.vz;
  const double *__restrict wx = s.wx, *__restrict wy = s.wy, *__restrict wz = s.wz;
  double *__restrict fx = sum.fx, *__restrict fy = sum.fy, *__restrict fz = sum.fz;
  double *__restrict tx = sum.tx, *__restrict ty = sum.ty, *__restrict tz = sum.tz;
  double *__restrict damp = sum.damp, *__restrict fric = sum.fric;
  const double nx = pl.normal.x, ny = pl.normal.y, nz = pl.normal.z;
  const double px = pl.point.x, py = pl.point.y, pz = pl.point.z;
#pragma GCC ivdep
  for (int q = 0; q < nc; ++q) {
    const int i = cand[q];
    const double phi = (x[i] - px) * nx + (y[i] - py) * ny + (z[i] - pz) * nz;
    const double ax = r * wx[i], ay = r * wy[i], az = r * wz[i];
    const double ux = vx[i] - (ay * nz - az * ny), uy = vy[i] - (az * nx - ax * nz), uz = vz[i] - (ax * ny - ay * nx);
    Hist c = load<kAccounts>(h, q);
    double f[3], m[3], de = 0, fe = 0;
    law.apply<kAccounts>(phi < r, nx, ny, nz, r - phi, ux, uy, uz, c, f, m, de, fe);
    store<kAccounts>(h, q, c);
    fx[i] += f[0], fy[i] += f[1], fz[i] += f[2];
    tx[i] -= r * m[0], ty[i] -= r * m[1], tz[i] -= r * m[2];
    if constexpr (kAccounts) damp[i] += de, fric[i] += fe;
  }
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void wall_loop(
    const State& s, const Terms& sum, const int* cand, const HistArrays& h, int nc, Plane pl, double r, Law law) {
  wall_candidates<false>(s, sum, cand, h, nc, pl, r, law);
}
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void wall_loop_accounts(
    const State& s, const Terms& sum, const int* cand, const HistArrays& h, int nc, Plane pl, double r, Law law) {
  wall_candidates<true>(s, sum, cand, h, nc, pl, r, law);
}

// The arrays of a history store (8 vectors; only xi sized without the accounts).
HistArrays arrays_of(std::vector<double> (&v)[8]) {
  return {{v[0].data(), v[1].data(), v[2].data()}, {v[3].data(), v[4].data(), v[5].data()}, v[6].data(), v[7].data()};
}

}  // namespace

StrippedDem::StrippedDem(const DemSolver& from, std::vector<Plane> walls, bool accounts)
    : accounts_(accounts), walls_(std::move(walls)) {
  const Particles& p = from.particles();
  const NeighborList& nl = from.neighbor_list();
  if (from.species().size() != 1) throw Error("stripped reference: one species only");
  if (!nl.valid_for(p) || nl.ghosts > 0 || nl.periodic.any())
    throw Error("stripped reference: needs the built lists of a serial run without periodic axes");
  n_ = static_cast<int>(p.size());
  dt_ = from.params().dt;
  skin_ = nl.skin;
  g_ = from.params().gravity;
  const auto& table = from.contact_table<contact::LinearSpringDashpot>();  // throws for another law
  pair_ = table.pair(0, 0);
  wall_ = table.wall(0);
  radius_ = n_ > 0 ? p.radius[0] : 0;
  inv_mass_ = n_ > 0 ? p.inv_mass[0] : 1;
  inv_inertia_ = n_ > 0 ? p.inv_inertia[0] : 1;
  mass_ = 1.0 / inv_mass_;
  for (int i = 0; i < n_; ++i)
    if (p.radius[i] != radius_) throw Error("stripped reference: the bed must be monodisperse");
  for (int a = 0; a < 3; ++a) {
    x_[a].resize(n_), v_[a].resize(n_), w_[a].resize(n_), f_[a].resize(n_), t_[a].resize(n_), x0_[a].resize(n_);
    for (int i = 0; i < n_; ++i) {
      x_[a][i] = p.x[i][a], v_[a][i] = p.v[i][a], w_[a][i] = p.omega[i][a];
      f_[a][i] = p.force[i][a], t_[a][i] = p.torque[i][a], x0_[a][i] = nl.x_at_build[i][a];
    }
  }
  damp_.assign(n_, 0.0), fric_.assign(n_, 0.0);
  if (accounts_) damp_ = p.e_damping, fric_ = p.e_friction;  // what the engine booked so far
  const int ne = static_cast<int>(nl.partner.size());
  offset_ = nl.offset;
  partner_ = nl.partner;
  owner_.resize(ne);
  for (int i = 0; i < n_; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) owner_[e] = i;
  auto take = [this](std::vector<double>(&to)[8], const contact::History& record) {
    const auto h = contact::LinearSpringDashpot::unpack(record);
    for (int a = 0; a < 3; ++a) to[a].push_back(h.xi[a]);
    if (!accounts_) return;
    for (int a = 0; a < 3; ++a) to[3 + a].push_back(h.ft[a]);
    to[6].push_back(h.vn), to[7].push_back(h.ftvt);
  };
  for (int e = 0; e < ne; ++e) take(hist_, nl.hist.get(e));
  // Wall candidates: the engine's (particles within r + skin of a wall part at the
  // build), grouped by wall; the planes here are the scene's parts in the same order.
  walls_cand_.assign(walls_.size(), {});
  for (int i = 0; i < n_; ++i)
    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) {
      const size_t part = nl.wall_part[e];
      if (part >= walls_.size()) throw Error("stripped reference: a wall part that is not one of the planes");
      WallCandidates& w = walls_cand_[part];
      w.particle.push_back(i);
      take(w.hist, nl.wall_hist[e]);
    }
}

void StrippedDem::forces() {
  for (int a = 0; a < 3; ++a) {
    double *__restrict f = f_[a].data(), *__restrict t = t_[a].data();
    const double fg = mass_ * g_[a];
    for (int i = 0; i < n_; ++i) f[i] = fg, t[i] = 0;
  }
  const State s{x_[0].data(), x_[1].data(), x_[2].data(), v_[0].data(), v_[1].data(),
                v_[2].data(), w_[0].data(), w_[1].data(), w_[2].data()};
  const Law pair_law = law_of(pair_, dt_), wall_law = law_of(wall_, dt_);
  const HistArrays hist = arrays_of(hist_);
  // Blocks of owners: the pair loop writes the block's shares into small buffers that stay
  // in the L1 cache, and they go straight into both particles (the torque on each is
  // -r n x F_t; the energy is booked to the owner) before the next block.
  const int *__restrict off = offset_.data(), *__restrict part = partner_.data();
  double *__restrict fx = f_[0].data(), *__restrict fy = f_[1].data(), *__restrict fz = f_[2].data();
  double *__restrict tx = t_[0].data(), *__restrict ty = t_[1].data(), *__restrict tz = t_[2].data();
  double *__restrict e_damp = damp_.data(), *__restrict e_fric = fric_.data();
  const double r = radius_;
  for (int i0 = 0; i0 < n_; i0 += kBlock) {
    const int i1 = std::min(n_, i0 + kBlock), e0 = off[i0], ne = off[i1] - e0;
    if (share_[0].size() < static_cast<size_t>(ne))
      for (auto& v : share_) v.resize(ne);
    // The block's part of the histories (without the accounts only xi is allocated).
    HistArrays h{{hist.xi[0] + e0, hist.xi[1] + e0, hist.xi[2] + e0}, {nullptr, nullptr, nullptr}, nullptr, nullptr};
    if (accounts_)
      h.ft[0] = hist.ft[0] + e0, h.ft[1] = hist.ft[1] + e0, h.ft[2] = hist.ft[2] + e0, h.vn = hist.vn + e0,
      h.ftvt = hist.ftvt + e0;
    const Terms out{share_[0].data(), share_[1].data(), share_[2].data(), share_[3].data(),
                     share_[4].data(), share_[5].data(), share_[6].data(), share_[7].data()};
    if (accounts_)
      pair_loop_accounts(s, owner_.data() + e0, partner_.data() + e0, h, out, ne, r, pair_law);
    else
      pair_loop(s, owner_.data() + e0, partner_.data() + e0, h, out, ne, r, pair_law);
    const double *__restrict cx = out.fx, *__restrict cy = out.fy, *__restrict cz = out.fz;  // index e - e0
    const double *__restrict mx = out.tx, *__restrict my = out.ty, *__restrict mz = out.tz;
    for (int i = i0; i < i1; ++i) {
      double sfx = fx[i], sfy = fy[i], sfz = fz[i], stx = tx[i], sty = ty[i], stz = tz[i];
      for (int e = off[i]; e < off[i + 1]; ++e) {
        const int j = part[e], k = e - e0;
        sfx += cx[k], sfy += cy[k], sfz += cz[k];
        fx[j] -= cx[k], fy[j] -= cy[k], fz[j] -= cz[k];
        const double ax = r * mx[k], ay = r * my[k], az = r * mz[k];
        stx -= ax, sty -= ay, stz -= az;
        tx[j] -= ax, ty[j] -= ay, tz[j] -= az;
      }
      fx[i] = sfx, fy[i] = sfy, fz[i] = sfz, tx[i] = stx, ty[i] = sty, tz[i] = stz;
    }
    if (accounts_) {
      const double *__restrict dd = out.damp, *__restrict df = out.fric;
      for (int i = i0; i < i1; ++i) {
        double sd = 0, sf = 0;
        for (int e = off[i]; e < off[i + 1]; ++e) sd += dd[e - e0], sf += df[e - e0];
        e_damp[i] += sd, e_fric[i] += sf;
      }
    }
  }
  const Terms sums{fx, fy, fz, tx, ty, tz, e_damp, e_fric};
  for (size_t k = 0; k < walls_.size(); ++k) {
    WallCandidates& w = walls_cand_[k];
    const int nc = static_cast<int>(w.particle.size());
    if (accounts_)
      wall_loop_accounts(s, sums, w.particle.data(), arrays_of(w.hist), nc, walls_[k], r, wall_law);
    else
      wall_loop(s, sums, w.particle.data(), arrays_of(w.hist), nc, walls_[k], r, wall_law);
  }
}

void StrippedDem::step() {
  const double hm = 0.5 * dt_ * inv_mass_, hi = 0.5 * dt_ * inv_inertia_, dt = dt_, limit2 = 0.25 * skin_ * skin_;
  double *__restrict x = x_[0].data(), *__restrict y = x_[1].data(), *__restrict z = x_[2].data();
  double *__restrict vx = v_[0].data(), *__restrict vy = v_[1].data(), *__restrict vz = v_[2].data();
  double *__restrict wx = w_[0].data(), *__restrict wy = w_[1].data(), *__restrict wz = w_[2].data();
  const double *__restrict fx = f_[0].data(), *__restrict fy = f_[1].data(), *__restrict fz = f_[2].data();
  const double *__restrict tx = t_[0].data(), *__restrict ty = t_[1].data(), *__restrict tz = t_[2].data();
  const double *__restrict x0 = x0_[0].data(), *__restrict y0 = x0_[1].data(), *__restrict z0 = x0_[2].data();
  int far = 0;  // particles farther than half the skin from where the lists were built
  for (int i = 0; i < n_; ++i) {
    vx[i] += hm * fx[i], vy[i] += hm * fy[i], vz[i] += hm * fz[i];
    wx[i] += hi * tx[i], wy[i] += hi * ty[i], wz[i] += hi * tz[i];
    x[i] += dt * vx[i], y[i] += dt * vy[i], z[i] += dt * vz[i];
    const double dx = x[i] - x0[i], dy = y[i] - y0[i], dz = z[i] - z0[i];
    far += !(dx * dx + dy * dy + dz * dz <= limit2);
  }
  if (far > 0)
    throw RunError(fmt::format("stripped reference: {} particle(s) moved more than half the skin ({:.3g} m) since "
                               "the lists were built; it does not rebuild lists (use a settled bed)",
                               far, 0.5 * skin_));
  forces();
  for (int i = 0; i < n_; ++i) {
    vx[i] += hm * fx[i], vy[i] += hm * fy[i], vz[i] += hm * fz[i];
    wx[i] += hi * tx[i], wy[i] += hi * ty[i], wz[i] += hi * tz[i];
  }
}

Vec3 StrippedDem::position(int i) const { return {x_[0][i], x_[1][i], x_[2][i]}; }
Vec3 StrippedDem::velocity(int i) const { return {v_[0][i], v_[1][i], v_[2][i]}; }
Vec3 StrippedDem::angular_velocity(int i) const { return {w_[0][i], w_[1][i], w_[2][i]}; }

double StrippedDem::kinetic_energy() const {
  double e = 0;
  for (int i = 0; i < n_; ++i) {
    const Vec3 v = velocity(i), w = angular_velocity(i);
    e += 0.5 * mass_ * dot(v, v) + 0.5 / inv_inertia_ * dot(w, w);
  }
  return e;
}

double StrippedDem::dissipated_damping() const {
  double e = 0;
  for (int i = 0; i < n_; ++i) e += damp_[i];
  return e;
}

double StrippedDem::dissipated_friction() const {
  double e = 0;
  for (int i = 0; i < n_; ++i) e += fric_[i];
  return e;
}

double StrippedDem::potential_energy() const {
  double e = 0;
  for (int i = 0; i < n_; ++i) e -= mass_ * dot(g_, position(i));
  return e;
}

}  // namespace cgdem::bench
