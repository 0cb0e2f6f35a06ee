#include "coupling/exchange.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

#include "fluid/boundary.hpp"

namespace cgdem::coupling {

Exchange::Exchange(const fluid::MacGrid& g, const std::vector<Species>& species, ExchangeParams params)
    : g_(g), params_(std::move(params)) {
  for (int a = 0; a < 3; ++a) periodic_[a] = params_.bc[2 * a].type == fluid::BcType::Periodic;
  for (const auto& s : species) {
    volume_.push_back(s.volume());
    d_original_.push_back(s.d_original);
    const double r = 0.5 * s.diameter();
    const auto it = std::find(radii_.begin(), radii_.end(), r);
    radius_group_.push_back(static_cast<int>(it - radii_.begin()));
    if (it == radii_.end()) radii_.push_back(r);
  }
  cells_ = cell_lattice(g_, periodic_);
  cell_layout_ = fluid::make_cell_field(g_);
  for (int d = 0; d < 3; ++d) faces_[d] = face_lattice(g_, d, periodic_);
  for (int d = 0; d < 3; ++d) {
    blocked_[d] = fluid::make_face_field(g_, d);
    const auto e = blocked_[d].extent();
    // Across the face (axes other than d) the ghost layers too: on a block over MPI ranks the
    // kernels reach the neighbour's boundary faces there (serially they are never read).
    const int g = fluid::kGhost;
    for (int h = 0; h < 2; ++h) {
      if (params_.bc[2 * d + h].type != fluid::BcType::Wall) continue;
      const int f = h == 0 ? 0 : e[d] - 1;
      for (int k = -g; k < e[2] + g; ++k)
        for (int j = -g; j < e[1] + g; ++j)
          for (int i = -g; i < e[0] + g; ++i) {
            const std::array<int, 3> q{i, j, k};
            if (q[d] == f) blocked_[d](i, j, k) = 1;
          }
    }
  }
}

Weights Exchange::cell_weights(const Vec3& x, const fluid::Field& layout) const {
  const bool w = walls_ && walls_->valid && walls_->any_solid;
  return masked(tsc_stencil(cells_, x), w ? walls_->alpha_cell : no_alpha_, layout);
}

Weights Exchange::face_weights(int d, const Vec3& x, const fluid::Field& layout) const {
  const bool w = walls_ && walls_->valid && walls_->any_solid;
  return masked(tsc_stencil(faces_[d], x), w ? walls_->alpha_face[d] : no_alpha_, blocked_[d], layout);
}

void Exchange::set_sync(fluid::FieldSync* sync) {
  sync_ = sync;
  std::array<bool, 6> cut{};
  for (int s = 0; s < 6; ++s) cut[s] = sync && sync->is_cut(s);
  cells_.ghost_side = cut;
  for (auto& L : faces_) L.ghost_side = cut;
}

void Exchange::weights(const Particles& p, size_t count, ParcelWeights& w) const {
  if (count > p.size()) throw Error("exchange: weights of more parcels than there are");
  const long n = static_cast<long>(count);
  w.cell.resize(n);
  for (auto& f : w.face) f.resize(n);
#pragma omp parallel for schedule(static) if (n >= 1024)
  for (long i = 0; i < n; ++i) {
    w.cell[i] = cell_weights(p.x[i], cell_layout_);
    for (int d = 0; d < 3; ++d) w.face[d][i] = face_weights(d, p.x[i], blocked_[d]);
  }
}

VoidStats Exchange::void_fraction(const Particles& p, fluid::Field& eps) const {
  ParcelWeights w;
  weights(p, w);
  return void_fraction(p, w, eps);
}

VoidStats Exchange::void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps) const {
  VoidFields vf;
  return void_fraction(p, w, eps, vf, false);
}

VoidStats Exchange::void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps,
                                  VoidFields& vf) const {
  return void_fraction(p, w, eps, vf, params_.wall_porosity == WallPorosity::Packing);
}

VoidStats Exchange::void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps, VoidFields& vf,
                                  bool packing) const {
  fluid::Field& vs = scratch_.vs;
  vs.resize(g_.nx, g_.ny, g_.nz);  // zeroed, in the storage of the last call
  // Per distinct parcel radius too, when the capacities are wanted for several radii.
  const size_t groups = packing ? radii_.size() : 0;
  std::vector<fluid::Field> vs_r(groups > 1 ? groups : 0, fluid::make_cell_field(g_));
  VoidStats st;
  for (size_t i = 0; i < w.size(); ++i) {  // serial: fixed summation order
    const double V = volume_[p.species[i]];
    deposit(w.cell[i], V, vs);
    if (!vs_r.empty()) deposit(w.cell[i], V, vs_r[radius_group_[p.species[i]]]);
    st.parcel_volume += V;
  }
  if (sync_) sync_->sum_deposits(vs, fluid::kCells);
  if (sync_)
    for (auto& f : vs_r) sync_->sum_deposits(f, fluid::kCells);
  const double vc = g_.dx * g_.dx * g_.dx;
  for (int k = 0; k < g_.nz; ++k)
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) {
        const double raw = 1 - vs(i, j, k) / vc;
        st.grid_volume += vs(i, j, k);
        st.eps_min_raw = std::min(st.eps_min_raw, raw);
        if (raw < params_.eps_min) ++st.clipped_cells;
        eps(i, j, k) = std::max(params_.eps_min, raw);
      }
  vf.mix = eps;
  vf.normalized = false;
  if (groups > 0) porosity_of_packing(vs, vs_r, vf, eps, st);
  if (sync_) sync_->fill_scalar(eps, fluid::ScalarKind::ZeroGradient);  // the parcels read it there
  return st;
}

// eps = max(eps_min, 1 - sum_r V_s,r/(C_r dx^3)) where some capacity is below 1; vf.cap the
// capacity the drag deposits are divided by (for several radii the solid-weighted harmonic
// mean sum V_s,r / sum (V_s,r/C_r), their smallest where no solid is).
void Exchange::porosity_of_packing(fluid::Field& vs, std::vector<fluid::Field>& vs_r, VoidFields& vf,
                                   fluid::Field& eps, VoidStats& st) const {
  std::vector<fluid::Field*> solid_r;  // per radius: one radius has all the solid
  if (vs_r.empty())
    solid_r.push_back(&vs);
  else
    for (auto& f : vs_r) solid_r.push_back(&f);
  const bool one = solid_r.size() == 1;
  if (sync_)  // the ghost layer's solid decides which nodes near a cut are evaluated
    for (auto* f : solid_r) sync_->copy_ghosts(*f, fluid::kCells);
  std::vector<fluid::Field>& cap = scratch_.cap;
  cap.resize(radii_.size());
  for (size_t r = 0; r < radii_.size(); ++r) {
    if (cap[r].extent() != g_.n()) cap[r] = fluid::make_cell_field(g_);
    const std::array<long, 2> nodes = capacity(radii_[r], *solid_r[r], cap[r]);
    for (int q = 0; q < 2; ++q) st.capacity_nodes[q] += nodes[q];
  }
  vf.cap = cap[0];
  const double vc = g_.dx * g_.dx * g_.dx;
  long normalized = 0;
#pragma omp parallel for schedule(static) if (g_.cells() > fluid::kOmpMinWork) reduction(+ : normalized)
  for (int k = 0; k < g_.nz; ++k)
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) {
        bool cut = false;
        for (const auto& c : cap) cut = cut || std::fabs(c(i, j, k) - 1.0) > 1e-12;  // C > 1 too: a mask moved weight there
        if (!cut) continue;
        double solid = 0, inv = 0, cmin = 1;
        for (size_t r = 0; r < cap.size(); ++r) {
          const double v = (*solid_r[r])(i, j, k), c = cap[r](i, j, k);
          cmin = std::min(cmin, c);
          if (!(v > 0)) continue;
          solid += v;
          inv += c > 0 ? v / c : INFINITY;
        }
        if (!one) vf.cap(i, j, k) = solid > 0 ? (std::isfinite(inv) ? solid / inv : 0.0) : cmin;
        if (!(solid > 0)) continue;
        ++normalized;
        // Bounded by the densest random packing unless the cell itself holds more solid: the
        // first layer of parcels on a wall is ordered (centres at r, where the estimate's
        // uniform reach puts few), and V_s/C over-counts it.
        const double phi = std::isfinite(inv) ? inv / vc : INFINITY;
        const double phi_l = phi <= params_.packing_max ? phi : std::max(params_.packing_max, solid / vc);
        eps(i, j, k) = std::max(params_.eps_min, 1 - phi_l);
      }
  if (sync_) sync_->copy_ghosts(vf.cap, fluid::kCells);
  st.normalized_cells = normalized;
  vf.normalized = sync_ ? sync_->any(normalized > 0) : normalized > 0;
}

double Exchange::face_capacity(int d, int i, int j, int k) const {
  const fluid::Field& c = void_fields_->cap;
  const std::array<int, 3> n = g_.n();
  std::array<int, 3> lo{i, j, k}, hi{i, j, k};
  lo[d] -= 1;  // face i lies between cells i-1 and i
  if (periodic_[d]) lo[d] = (lo[d] + n[d]) % n[d], hi[d] %= n[d];
  const bool has_lo = lo[d] >= 0 || cells_.ghost_side[2 * d], has_hi = hi[d] < n[d] || cells_.ghost_side[2 * d + 1];
  if (has_lo && has_hi) return 0.5 * (c(lo[0], lo[1], lo[2]) + c(hi[0], hi[1], hi[2]));
  return has_lo ? c(lo[0], lo[1], lo[2]) : c(hi[0], hi[1], hi[2]);
}

void Exchange::porosity_source(const VoidFields& now, const fluid::Field& mix_old, const fluid::Field& eps_new,
                               const fluid::Field& eps_old, double dt_f, fluid::Field& mass) const {
  if (params_.wall_porosity == WallPorosity::Cell) {  // eps is the whole cell's non-solid part: no source
    mass = fluid::Field{};
    return;
  }
  const std::array<int, 3> n = g_.n();
  mass = fluid::make_cell_field(g_);
  fluid::Field share = fluid::make_cell_field(g_);  // mix - eps at t^{n+1}: the walls' share
  bool any = false;  // each cell on its own: the threads' split changes nothing
#pragma omp parallel for schedule(static) reduction(|| : any) if (g_.cells() > fluid::kOmpMinWork)
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const double m = ((now.mix(i, j, k) - mix_old(i, j, k)) - (eps_new(i, j, k) - eps_old(i, j, k))) / dt_f;
        mass(i, j, k) = m;
        share(i, j, k) = now.mix(i, j, k) - eps_new(i, j, k);
        any = any || m != 0 || share(i, j, k) != 0;
      }
  if (!(sync_ ? sync_->any(any) : any)) {
    mass = fluid::Field{};
    return;
  }
  if (!(frame_ && frame_->scene && !frame_->scene->empty())) return;
  if (sync_) sync_->copy_ghosts(share, fluid::kCells);
  // The walls' share of the non-solid volume, mix - eps, moves with the wall: the flux
  // (mix_f - E_f) U_B through the faces of the cells where they differ, U_B the velocity of
  // the nearest wall (the domain's boundary faces are the sides' business; a cut between
  // ranks is not a boundary: its faces are handled by both blocks, each for its own cell).
  // Each face once: by its low cell when that holds a share, else by its high cell.
  std::array<int, 3> lo_c{}, hi_c{};  // cells visited: the block's and its ghost layer on cut sides
  for (int d = 0; d < 3; ++d)
    lo_c[d] = cells_.ghost_side[2 * d] ? -1 : 0, hi_c[d] = cells_.ghost_side[2 * d + 1] ? n[d] : n[d] - 1;
  auto own = [&](const std::array<int, 3>& c) {
    return c[0] >= 0 && c[0] < n[0] && c[1] >= 0 && c[1] < n[1] && c[2] >= 0 && c[2] < n[2];
  };
  auto share_at = [&](std::array<int, 3> c) {
    for (int d = 0; d < 3; ++d) {
      if (periodic_[d]) c[d] = (c[d] + n[d]) % n[d];
      if (c[d] < lo_c[d] || c[d] > hi_c[d]) return 0.0;
    }
    return share(c[0], c[1], c[2]);
  };
  // Face f of axis d between cells lo and hi = f (each maybe outside the block).
  auto face_flux = [&](int d, std::array<int, 3> lo, std::array<int, 3> f) {
    const bool boundary_lo = !periodic_[d] && f[d] == 0 && !cells_.ghost_side[2 * d];
    const bool boundary_hi = !periodic_[d] && f[d] == n[d] && !cells_.ghost_side[2 * d + 1];
    if (boundary_lo || boundary_hi) return;
    const double ws = 0.5 * (share_at(lo) + share_at(f));
    if (ws == 0) return;
    const double ub = frame_->wall_velocity(g_.face_centre(d, f[0], f[1], f[2]))[d];
    if (ub == 0) return;
    const double flux = ws * ub / g_.dx;
    std::array<int, 3> hi = f;
    if (periodic_[d]) lo[d] = (lo[d] + n[d]) % n[d], hi[d] = hi[d] % n[d];
    if (own(hi)) mass(hi[0], hi[1], hi[2]) -= flux;  // leaves through hi's low face
    if (own(lo)) mass(lo[0], lo[1], lo[2]) += flux;  // enters through lo's high face
  };
  for (int k = lo_c[2]; k <= hi_c[2]; ++k)
    for (int j = lo_c[1]; j <= hi_c[1]; ++j)
      for (int i = lo_c[0]; i <= hi_c[0]; ++i) {
        if (share(i, j, k) == 0) continue;
        const std::array<int, 3> c{i, j, k};
        for (int d = 0; d < 3; ++d) {
          const std::array<int, 3> u = fluid::unit(d);
          const std::array<int, 3> below{i - u[0], j - u[1], k - u[2]}, up{i + u[0], j + u[1], k + u[2]};
          face_flux(d, c, up);                                  // high face: c is its low cell
          if (share_at(below) == 0) face_flux(d, below, c);     // low face, unless below handles it
        }
      }
}

const std::array<fluid::Field, 3>& Exchange::pressure_gradient(const fluid::FluidState& air) const {
  fluid::Field& pg = grad_scratch_.p;
  pg = air.p;  // the storage is reused once it has the grid's size
  if (sync_)
    sync_->fill_scalar(pg, fluid::ScalarKind::Pressure);
  else
    fluid::fill_scalar_ghosts(g_, params_.bc, pg, fluid::ScalarKind::Pressure);
  std::array<fluid::Field, 3>& grad = grad_scratch_.grad;
  for (int d = 0; d < 3; ++d) {
    // Made once: the faces the loop below leaves alone (the outermost layer along d) keep
    // the zeros they were made with.
    if (grad[d].empty()) grad[d] = fluid::make_face_field(g_, d);
    const auto e = grad[d].extent();
    const auto u = fluid::unit(d);
    // Every face whose two cells exist, ghost layers included: on a block over MPI ranks
    // the kernels of parcels next to a cut read them (serially only interior faces are read).
    const int g = fluid::kGhost;
    std::array<int, 3> lo{-g, -g, -g}, hi{e[0] + g, e[1] + g, e[2] + g};
    lo[d] = -g + 1, hi[d] = e[d] + g - 1;
    fluid::Field& gd = grad[d];
    const long faces = static_cast<long>(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
#pragma omp parallel for schedule(static) if (faces > fluid::kOmpMinWork)
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i) gd(i, j, k) = (pg(i, j, k) - pg(i - u[0], j - u[1], k - u[2])) / g_.dx;
  }
  return grad;
}

Exchange::AirSample Exchange::sample(const fluid::FluidState& air, const std::array<fluid::Field, 3>& grad,
                                     const ParcelWeights& w, size_t i) const {
  AirSample a;
  const Weights& wc = w.cell[i];
  a.eps = interpolate(wc, air.eps);
  for (int d = 0; d < 3; ++d) {
    a.u[d] = interpolate(w.face[d][i], air.vel(d));
    a.grad_p[d] = interpolate_cell_faces(wc, air.eps, d, grad[d]);
  }
  return a;
}

void Exchange::air_to_parcels(const fluid::FluidState& air, const ParcelWeights& w, Particles& p) const {
  const auto& grad = pressure_gradient(air);
  const int n = static_cast<int>(w.size());
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (int i = 0; i < n; ++i) {
    const int s = p.species[i];
    const AirSample a = sample(air, grad, w, i);
    const double slip = norm(a.u - p.v[i]);
    p.u_fluid[i] = a.u;
    p.drag[i] = volume_[s] * beta_over_solid(params_.law, a.eps, slip, d_original_[s], params_.air);  // eq. (8)
    p.f_ext[i] = -volume_[s] * a.grad_p;
  }
}

template <class Impulse>
void Exchange::kick_parcels(const fluid::FluidState& air, const ParcelWeights& w, Particles& p, Impulse impulse) const {
  const long n = static_cast<long>(w.size());
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long i = 0; i < n; ++i) {
    Vec3 u;
    for (int d = 0; d < 3; ++d) u[d] = interpolate(w.face[d][i], air.vel(d));
    const Vec3 dj = impulse(i, u);
    const Vec3 v0 = p.v[i];
    p.v[i] += p.inv_mass[i] * dj;
    p.j_drag[i] += dj;
    p.w_fluid[i] += dot(dj, 0.5 * (v0 + p.v[i]));
  }
}

void Exchange::correct_parcels(const fluid::FluidState& air, const ParcelWeights& w, double dt_f,
                               Particles& p) const {
  kick_parcels(air, w, p, [&](long i, const Vec3& u) {
    const double a = dt_f * p.drag[i];
    return (a / (1 + a * p.inv_mass[i])) * (u - p.u_fluid[i]);
  });
}

template <class Coefficients>
void Exchange::deposit_sources(const ParcelWeights& w, fluid::Sources& src, Coefficients coef) const {
  // The coefficients first; then each of the six fields (K and Kv of each component) takes
  // its deposits from one thread, parcel after parcel: every sum in a fixed order, so the
  // fields are the same bits for any number of threads.
  const long n = static_cast<long>(w.size());
  std::vector<double> kc(n);
  std::vector<Vec3> kvc(n);
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long i = 0; i < n; ++i) std::tie(kc[i], kvc[i]) = coef(static_cast<size_t>(i));
#pragma omp parallel for schedule(dynamic, 1)
  for (int task = 0; task < 6; ++task) {
    const int d = task / 2;
    const bool v = task % 2 == 1;
    fluid::Field f = fluid::make_face_field(g_, d);
    for (long i = 0; i < n; ++i)
      if (kc[i] != 0) deposit(w.face[d][i], v ? kvc[i][d] : kc[i], f);
    (v ? src.Kv[d] : src.K[d]) = std::move(f);
  }
  for (int d = 0; d < 3; ++d) {
    sync_periodic_face(d, periodic_, src.K[d]);
    sync_periodic_face(d, periodic_, src.Kv[d]);
    if (sync_) sync_->sum_deposits(src.K[d], d), sync_->sum_deposits(src.Kv[d], d);
  }
  if (!(void_fields_ && void_fields_->normalized)) return;
  // Per volume the packing fills: K/C_f, Kv/C_f where the capacity is below 1.
  for (int d = 0; d < 3; ++d) {
    const auto e = src.K[d].extent();
#pragma omp parallel for schedule(static) if (static_cast<long>(e[0]) * e[1] * e[2] > fluid::kOmpMinWork)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          if (src.K[d](i, j, k) == 0) continue;
          const double c = face_capacity(d, i, j, k);
          if (c >= 1.0) continue;
          // The quadrature resolves a sub-cube (1/27 of a cell): a smaller capacity under a
          // drag deposit is a stray of the kernel, not a smaller volume to spread it over.
          const double inv = 1.0 / std::max(c, 1.0 / 27);
          src.K[d](i, j, k) *= inv;
          src.Kv[d](i, j, k) *= inv;
        }
  }
}

void Exchange::mean_parcel_velocities(const Particles& p, size_t n, double dt_f, std::vector<Vec3>& vbar) const {
  if (n > p.size()) throw Error("exchange: mean velocities of more parcels than there are");
  vbar.resize(n);
  const long m = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (m >= 2048)
  for (long i = 0; i < m; ++i)
    vbar[i] = p.drag[i] > 0 ? p.u_fluid[i] - (1.0 / (dt_f * p.drag[i])) * p.j_drag[i] : p.v[i];
}

void Exchange::drag_at(const fluid::FluidState& air, const ParcelWeights& w, const Particles& p,
                       const std::vector<Vec3>& vbar, std::vector<double>& c) const {
  const long n = static_cast<long>(w.size());
  if (vbar.size() != w.size()) throw Error("exchange: drag_at needs one mean velocity per parcel");
  c.resize(n);
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long i = 0; i < n; ++i) {
    const int s = p.species[i];
    Vec3 u;
    for (int d = 0; d < 3; ++d) u[d] = interpolate(w.face[d][i], air.vel(d));
    const double eps = interpolate(w.cell[i], air.eps);
    c[i] = volume_[s] * beta_over_solid(params_.law, eps, norm(u - vbar[i]), d_original_[s], params_.air);
  }
}

void Exchange::deposit_drag(const ParcelWeights& w, const std::vector<double>& c, const std::vector<Vec3>& vbar,
                            fluid::Sources& src) const {
  if (c.size() != w.size() || vbar.size() != w.size())
    throw Error("exchange: deposit_drag needs one coefficient and one mean velocity per parcel");
  const double inv_vc = 1.0 / (g_.dx * g_.dx * g_.dx);
  deposit_sources(w, src, [&](size_t i) {
    const double k = c[i] * inv_vc;
    return std::pair{k, k * vbar[i]};
  });
}

void Exchange::correct_parcels_implicit(const fluid::FluidState& air, const ParcelWeights& w, double dt_f,
                                        const std::vector<double>& c, const std::vector<Vec3>& vbar,
                                        Particles& p) const {
  if (c.size() != w.size() || vbar.size() != w.size())
    throw Error("exchange: correct_parcels_implicit needs one coefficient and one mean velocity per parcel");
  kick_parcels(air, w, p, [&](long i, const Vec3& u) {
    const double a = dt_f * c[i];
    return (1.0 / (1 + a * p.inv_mass[i])) * (a * (u - vbar[i]) - p.j_drag[i]);
  });
}

void Exchange::parcels_to_air(const Particles& p, const ParcelWeights& w, double dt_f, fluid::Sources& src) const {
  const double inv_vc = 1.0 / (g_.dx * g_.dx * g_.dx);
  deposit_sources(w, src, [&](size_t i) {
    const double c = p.drag[i] * inv_vc;
    return std::pair{c, inv_vc * (p.drag[i] * p.u_fluid[i] - (1.0 / dt_f) * p.j_drag[i])};  // c, c vbar
  });
}

}  // namespace cgdem::coupling
