// No floating-point contraction: the x86-64-v3 build of the kicks (which has FMA) computes
// the same bits as the baseline one.
#pragma GCC optimize("fp-contract=off")
#include "solvers/dem/dem_solver.hpp"

#include <omp.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/error.hpp"

namespace cgdem {

DemSolver::DemSolver(std::vector<Species> species, const contact::ContactModel& material, const DemParams& params,
                     geometry::Scene scene)
    : species_(std::move(species)),
      tables_(contact::make_tables(species_, material)),
      params_(params),
      scene_(std::move(scene)) {
  if (params_.skin <= 0) {
    double dmax = 0;
    for (const auto& s : species_) dmax = std::max(dmax, s.diameter());
    params_.skin = 0.1 * dmax;
  }
  nl_.skin = params_.skin;
  nl_.set_accounts(params_.accounts);
  nl_.periodic.axis = params_.periodic;
  nl_.periodic.lo = params_.domain.lo;
  nl_.periodic.hi = params_.domain.hi;
  for (int a = 0; a < 3; ++a)
    if (params_.periodic[a] && !(std::isfinite(params_.domain.lo[a]) && std::isfinite(params_.domain.hi[a]) &&
                                 params_.domain.hi[a] > params_.domain.lo[a]))
      throw ConfigError(fmt::format("periodic axis {} needs a finite domain on that axis", "xyz"[a]));
  t_kick_ = timers_.id("integrate");
  t_neigh_ = timers_.id("neighbour lists");
  t_force_ = timers_.id("contact forces");
  t_drift_ = timers_.id("integrate");
}

namespace {

// The arrays a half kick reads and writes, as plain pointers to their doubles (a Vec3 is
// three): the loops below then keep them in registers instead of reloading each vector's
// data pointer after every store, and the compiler can vectorize over particles.
struct KickArrays {
  double* __restrict v;
  double* __restrict omega;
  const double* __restrict force;
  const double* __restrict torque;
  const double* __restrict f_ext;
  const double* __restrict u_fluid;
  double* __restrict j_drag;
  double* __restrict w_fluid;
  const double* __restrict drag;
  const double* __restrict inv_mass;
  const double* __restrict inv_inertia;
  explicit KickArrays(Particles& p)
      : v(reinterpret_cast<double*>(p.v.data())),
        omega(reinterpret_cast<double*>(p.omega.data())),
        force(reinterpret_cast<double*>(p.force.data())),
        torque(reinterpret_cast<double*>(p.torque.data())),
        f_ext(reinterpret_cast<double*>(p.f_ext.data())),
        u_fluid(reinterpret_cast<double*>(p.u_fluid.data())),
        j_drag(reinterpret_cast<double*>(p.j_drag.data())),
        w_fluid(p.w_fluid.data()),
        drag(p.drag.data()),
        inv_mass(p.inv_mass.data()),
        inv_inertia(p.inv_inertia.data()) {}
};
static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_standard_layout_v<Vec3>,
              "KickArrays reads a Vec3 array as doubles");

// Half kicks (see the header) and the drift of the particles i0..i1-1, in blocks of kBlock
// particles whose data and factors stay in cache between the loops. Per half kick:
//   v1 = (1/(1 + hm c)) (v0 + hm (F + c u)),   hm = h/m,  c = drag,  u = u_fluid
//   j = (h c)(u - v1),  j_drag += j,  w_fluid += dot(h f_ext + j, (v0 + v1)/2),  v = v1
// (without air: v += hm F), and omega += (h/I) T. `kKicks` half kicks with the same forces
// (2: the one that closes the previous step and the one that opens this one), then, with
// kDrift, x += dt v; with kBuild, returns how far the particles moved since the build
// (MoveBounds: max |x - x_at_build|^2 and the least and greatest displacement per axis; NaN
// ignored, as in NeighborList::needs_rebuild).
// Each particle sees the operations of the Vec3 expressions above in their order, so the
// result is the same to the bit as kicking particle by particle. The per-particle factors
// are spread to one value per component so that the arithmetic runs over the components as
// one flat array (vectorized); the sums over components (the dot product) go back to one
// value per particle in the Vec3 order ((x + y) + z).
template <bool kAir, int kKicks, bool kDrift, bool kBuild>
__attribute__((target_clones("arch=x86-64-v3", "default"))) MoveBounds kicks_and_drift_range(
    const KickArrays& a, double* __restrict x, const double* __restrict x0, int i0, int i1, double h, double dt) {
  constexpr int kBlock = 256;
  alignas(64) double hm1[kBlock], s1[kBlock], hc1[kBlock], hi1[kBlock];  // per particle
  alignas(64) double hm3[3 * kBlock], s3[3 * kBlock], c3[3 * kBlock], hc3[3 * kBlock], hi3[3 * kBlock];
  alignas(64) double term[3 * kBlock];
  MoveBounds moved;
  for (int b0 = i0; b0 < i1; b0 += kBlock) {
    const int n = std::min(i1 - b0, kBlock), m = 3 * n;
    const int k0 = 3 * b0;
    double* __restrict v = a.v + k0;
    double* __restrict w = a.omega + k0;
    const double* __restrict F = a.force + k0;
    const double* __restrict T = a.torque + k0;
    // The per-particle factors, then one per component.
    for (int q = 0; q < n; ++q) {
      hm1[q] = h * a.inv_mass[b0 + q];
      hi1[q] = h * a.inv_inertia[b0 + q];
      if (kAir) {
        const double c = a.drag[b0 + q];
        s1[q] = 1.0 / (1.0 + hm1[q] * c);
        hc1[q] = h * c;
      }
    }
    for (int q = 0; q < n; ++q)
      for (int d = 0; d < 3; ++d) {
        hm3[3 * q + d] = hm1[q];
        hi3[3 * q + d] = hi1[q];
        if (kAir) {
          s3[3 * q + d] = s1[q];
          c3[3 * q + d] = a.drag[b0 + q];
          hc3[3 * q + d] = hc1[q];
        }
      }
    for (int kick = 0; kick < kKicks; ++kick) {
      if (kAir) {
        const double* __restrict u = a.u_fluid + k0;
        const double* __restrict fe = a.f_ext + k0;
        double* __restrict jd = a.j_drag + k0;
        for (int r = 0; r < m; ++r) {
          const double v0 = v[r];
          const double v1 = s3[r] * (v0 + hm3[r] * (F[r] + c3[r] * u[r]));
          const double j = hc3[r] * (u[r] - v1);
          jd[r] += j;
          term[r] = (h * fe[r] + j) * (0.5 * (v0 + v1));
          v[r] = v1;
        }
        for (int q = 0; q < n; ++q) a.w_fluid[b0 + q] += term[3 * q] + term[3 * q + 1] + term[3 * q + 2];
      } else {
        for (int r = 0; r < m; ++r) v[r] += hm3[r] * F[r];
      }
      for (int r = 0; r < m; ++r) w[r] += hi3[r] * T[r];
    }
    if (kDrift)
      for (int r = 0; r < m; ++r) x[k0 + r] += dt * v[r];
    if (kBuild) {  // branch-free selects (a NaN compares false and is passed over)
      double m2 = moved.max2, lx = moved.lo.x, ly = moved.lo.y, lz = moved.lo.z, hx = moved.hi.x, hy = moved.hi.y,
             hz = moved.hi.z;
      for (int q = 0; q < n; ++q) {
        const int k = k0 + 3 * q;
        const double dx = x[k] - x0[k], dy = x[k + 1] - x0[k + 1], dz = x[k + 2] - x0[k + 2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        m2 = d2 > m2 ? d2 : m2;
        lx = dx < lx ? dx : lx, hx = dx > hx ? dx : hx;
        ly = dy < ly ? dy : ly, hy = dy > hy ? dy : hy;
        lz = dz < lz ? dz : lz, hz = dz > hz ? dz : hz;
      }
      moved.max2 = m2, moved.lo = {lx, ly, lz}, moved.hi = {hx, hy, hz};
    }
  }
  return moved;
}

// The particles 0..n-1 (the owned ones: ghosts are refreshed from their owners), split
// evenly between the threads.
template <bool kAir, int kKicks, bool kDrift, bool kBuild>
MoveBounds kicks_and_drift_t(Particles& p, int n, const std::vector<Vec3>& x_at_build, double h, double dt) {
  const KickArrays a(p);
  double* x = reinterpret_cast<double*>(p.x.data());
  const double* x0 = kBuild ? reinterpret_cast<const double*>(x_at_build.data()) : nullptr;
  // The threads' bounds combined by minimum and maximum: exact, whatever the split.
  const MoveBounds none;
  double max2 = 0, lo[3] = {none.lo.x, none.lo.y, none.lo.z}, hi[3] = {none.hi.x, none.hi.y, none.hi.z};
#pragma omp parallel reduction(max : max2, hi[:3]) reduction(min : lo[:3]) if (n >= 512)
  {
    const long nt = omp_get_num_threads(), t = omp_get_thread_num();
    const int i0 = static_cast<int>(n * t / nt), i1 = static_cast<int>(n * (t + 1) / nt);
    const MoveBounds m = kicks_and_drift_range<kAir, kKicks, kDrift, kBuild>(a, x, x0, i0, i1, h, dt);
    max2 = std::max(max2, m.max2);
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], m.lo[d]), hi[d] = std::max(hi[d], m.hi[d]);
  }
  MoveBounds moved;
  moved.max2 = max2;
  moved.lo = {lo[0], lo[1], lo[2]};
  moved.hi = {hi[0], hi[1], hi[2]};
  return moved;
}

template <bool kAir>
MoveBounds kicks_and_drift_air(Particles& p, int n, const std::vector<Vec3>& x_at_build, double h, double dt,
                               bool close) {
  const bool build = x_at_build.size() == p.size();
  if (close)
    return build ? kicks_and_drift_t<kAir, 2, true, true>(p, n, x_at_build, h, dt)
                 : kicks_and_drift_t<kAir, 2, true, false>(p, n, x_at_build, h, dt);
  return build ? kicks_and_drift_t<kAir, 1, true, true>(p, n, x_at_build, h, dt)
               : kicks_and_drift_t<kAir, 1, true, false>(p, n, x_at_build, h, dt);
}

// With `close`, the half kick that ends the previous step, then (always) the half kick
// that starts this one and the drift, in one pass; returns how far the particles moved
// since the build, for the rebuild test (nothing when there is no build yet).
MoveBounds kicks_and_drift(Particles& p, int n, const std::vector<Vec3>& x_at_build, double h, double dt, bool air,
                           bool close) {
  return air ? kicks_and_drift_air<true>(p, n, x_at_build, h, dt, close)
             : kicks_and_drift_air<false>(p, n, x_at_build, h, dt, close);
}

}  // namespace

void DemSolver::kick(double h) {
  const std::vector<Vec3> none;
  if (air_forces_)
    kicks_and_drift_t<true, 1, false, false>(p_, static_cast<int>(owned()), none, h, 0);
  else
    kicks_and_drift_t<false, 1, false, false>(p_, static_cast<int>(owned()), none, h, 0);
}

// Owned particles only: a hook removes the ghosts before (DomainExchange::drop_ghosts).
void DemSolver::remove_escaped() {
  if (nl_.ghosts > 0) throw Error("DemSolver: escaped parcels are removed only after the ghosts were dropped");
  std::vector<int> keep;
  keep.reserve(p_.size());
  for (size_t i = 0; i < p_.size(); ++i) {
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (!params_.periodic[a]) inside = inside && p_.x[i][a] >= params_.domain.lo[a] && p_.x[i][a] <= params_.domain.hi[a];
    if (inside) {
      keep.push_back(static_cast<int>(i));
    } else {
      removed_damping_ += p_.e_damping[i];
      removed_friction_ += p_.e_friction[i];
      removed_walls_ += p_.w_walls[i];
      removed_fluid_ += p_.w_fluid[i];
      ++removed_;
    }
  }
  if (keep.size() != p_.size()) {
    p_.reorder(keep);
    // Serial: the lists are dropped, and with them every history (the behaviour the serial
    // results were made with). With a hook the histories of the others are kept: the lists
    // follow the removal, and the pairs with ghosts are records by id already.
    if (exchange_)
      nl_.retain(keep, 0);
    else
      nl_.offset.clear();
  }
}

// Rebuilds the lists at x^n (the escaped parcels removed first).
void DemSolver::rebuild_lists() {
  if (exchange_) {
    exchange_->drop_ghosts(p_, nl_);
    remove_escaped();
    exchange_->rebuild(p_, nl_, frame_);
  } else {
    remove_escaped();
    nl_.build(p_, frame_);
  }
}

void DemSolver::step() { advance(1); }

// advance(n) is n calls of step(), bit for bit: between two of its steps the closing half
// kick of one and the opening half kick and drift of the next share a pass.
void DemSolver::advance(long n) {
  if (n <= 0) return;
  const double dt = params_.dt;
  if (!forces_valid_) {  // first step (or particles were added): forces at x^n
    frame_ = scene_.at(t_);
    if (!exchange_) nl_.offset.clear();  // (a hook keeps the lists in step with its ghosts)
    {
      auto scope = timers_.scope(t_neigh_);
      rebuild_lists();
    }
    compute_forces();
    forces_valid_ = true;
  }
  for (long k = 0; k < n; ++k) {
    MoveBounds moved;
    {
      auto scope = timers_.scope(t_kick_);
      moved = kicks_and_drift(p_, static_cast<int>(owned()), nl_.x_at_build, 0.5 * dt, dt, air_forces_, k > 0);
    }
    t_ += dt;
    ++steps_;
    frame_ = scene_.at(t_);
    {
      auto scope = timers_.scope(t_neigh_);
      // One block: the test of the relative displacements too (neighbor_list.hpp); a run
      // over several keeps each particle's own below skin/2 for its ghost layers.
      const bool relative = !exchange_ || exchange_->relative_rebuild_test();
      bool rebuild = nl_.needs_rebuild(moved, p_.size(), frame_, relative);
      if (exchange_) rebuild = exchange_->any(rebuild);
      if (rebuild)
        rebuild_lists();
      else if (exchange_)
        exchange_->refresh_ghosts(p_);
    }
    compute_forces();
  }
  auto scope = timers_.scope(t_kick_);
  kick(0.5 * dt);
}

void DemSolver::resume(double t, long steps, long removed, const EnergyBudget& removed_accounts, Particles parcels,
                       NeighborList::Incoming histories) {
  for (int s : parcels.species)
    if (s < 0 || s >= static_cast<int>(species_.size())) throw Error("resume: unknown species index");
  p_ = std::move(parcels);
  NeighborList lists;  // none yet: the first step builds them
  lists.skin = nl_.skin;
  lists.set_accounts(params_.accounts);
  lists.periodic = nl_.periodic;
  lists.builds = nl_.builds;
  lists.incoming = std::move(histories);
  nl_ = std::move(lists);
  t_ = t;
  steps_ = steps;
  removed_ = removed;
  removed_damping_ = removed_accounts.dissipated_damping;
  removed_friction_ = removed_accounts.dissipated_friction;
  removed_walls_ = removed_accounts.work_walls;
  removed_fluid_ = removed_accounts.work_fluid;
  frame_ = scene_.at(t_);
  forces_valid_ = true;  // the parcels carry the forces of step `steps`
}

EnergyBudget DemSolver::removed_accounts() const {
  EnergyBudget b;
  b.dissipated_damping = removed_damping_;
  b.dissipated_friction = removed_friction_;
  b.work_walls = removed_walls_;
  b.work_fluid = removed_fluid_;
  return b;
}

long DemSolver::contact_count() const {
  long c = 0;
  const size_t n = owned();
  for (size_t i = 0; i < n; ++i) {
    for (int e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e) {
      const int j = nl_.partner[e];
      if (static_cast<size_t>(j) >= n && p_.id[j] < p_.id[i]) continue;  // counted on the ghost's rank
      const double r = p_.radius[i] + p_.radius[j];
      if (norm2(p_.x[i] - nl_.partner_x(p_, e)) < r * r) ++c;
    }
    for (int e = nl_.wall_offset[i]; e < nl_.wall_offset[i + 1]; ++e)
      if (frame_.part_distance(nl_.wall_part[e], p_.x[i]) < p_.radius[i]) ++c;
  }
  return c;
}

}  // namespace cgdem
