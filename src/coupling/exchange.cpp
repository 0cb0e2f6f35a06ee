#include "coupling/exchange.hpp"

#include <algorithm>
#include <utility>

#include "fluid/boundary.hpp"

namespace cgdem::coupling {

Exchange::Exchange(const fluid::MacGrid& g, const std::vector<Species>& species, ExchangeParams params)
    : g_(g), params_(std::move(params)) {
  for (int a = 0; a < 3; ++a) periodic_[a] = params_.bc[2 * a].type == fluid::BcType::Periodic;
  for (const auto& s : species) {
    volume_.push_back(s.volume());
    d_original_.push_back(s.d_original);
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
  fluid::Field vs = fluid::make_cell_field(g_);
  VoidStats st;
  for (size_t i = 0; i < w.size(); ++i) {  // serial: fixed summation order
    const double V = volume_[p.species[i]];
    deposit(w.cell[i], V, vs);
    st.parcel_volume += V;
  }
  if (sync_) sync_->sum_deposits(vs, fluid::kCells);
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
  if (sync_) sync_->fill_scalar(eps, fluid::ScalarKind::ZeroGradient);  // the parcels read it there
  return st;
}

std::array<fluid::Field, 3> Exchange::pressure_gradient(const fluid::FluidState& air) const {
  fluid::Field pg = air.p;
  if (sync_)
    sync_->fill_scalar(pg, fluid::ScalarKind::Pressure);
  else
    fluid::fill_scalar_ghosts(g_, params_.bc, pg, fluid::ScalarKind::Pressure);
  std::array<fluid::Field, 3> grad;
  for (int d = 0; d < 3; ++d) {
    grad[d] = fluid::make_face_field(g_, d);
    const auto e = grad[d].extent();
    const auto u = fluid::unit(d);
    // Every face whose two cells exist, ghost layers included: on a block over MPI ranks
    // the kernels of parcels next to a cut read them (serially only interior faces are read).
    const int g = fluid::kGhost;
    std::array<int, 3> lo{-g, -g, -g}, hi{e[0] + g, e[1] + g, e[2] + g};
    lo[d] = -g + 1, hi[d] = e[d] + g - 1;
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i)
          grad[d](i, j, k) = (pg(i, j, k) - pg(i - u[0], j - u[1], k - u[2])) / g_.dx;
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
  const auto grad = pressure_gradient(air);
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
  for (int d = 0; d < 3; ++d) {
    src.K[d] = fluid::make_face_field(g_, d);
    src.Kv[d] = fluid::make_face_field(g_, d);
  }
  for (size_t i = 0; i < w.size(); ++i) {  // serial: fixed summation order
    const auto [k, kv] = coef(i);
    if (k == 0) continue;
    for (int d = 0; d < 3; ++d) {
      deposit(w.face[d][i], k, src.K[d]);
      deposit(w.face[d][i], kv[d], src.Kv[d]);
    }
  }
  for (int d = 0; d < 3; ++d) {
    sync_periodic_face(d, periodic_, src.K[d]);
    sync_periodic_face(d, periodic_, src.Kv[d]);
    if (sync_) sync_->sum_deposits(src.K[d], d), sync_->sum_deposits(src.Kv[d], d);
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
