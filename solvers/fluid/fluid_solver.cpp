// FluidSolver: the step sequence (advance), predictor and time-step limits.
// The equations are in fluid_solver.hpp; the pressure projection is in projection.cpp.
#include "solvers/fluid/fluid_solver.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

namespace cgdem::fluid {

namespace {

FaceRange active_range(const MacGrid& g, const FluidBoundary& bc, int d) {
  FaceRange r{};
  for (int a = 0; a < 3; ++a) r[a] = {0, g.n()[a]};
  r[d] = active_face_range(g, bc, d);
  return r;
}

void check_source(const Field& f, const MacGrid& g, int d, const char* name) {
  if (!f.empty() && f.extent() != g.face_extent(d))
    throw Error(fmt::format("fluid sources: {}[{}] does not have the face layout of the grid", name, d));
}

}  // namespace

pressure::GridSpec pressure_grid(const MacGrid& g, const FluidParams& params) {
  pressure::GridSpec gs;
  gs.nx = g.nx, gs.ny = g.ny, gs.nz = g.nz;
  gs.dx = gs.dy = gs.dz = g.dx;
  for (int s = 0; s < 6; ++s) {
    BcType t = params.bc[s].type;
    gs.bc[s] = t == BcType::Wall ? pressure::Boundary::Wall
                                 : (t == BcType::Open ? pressure::Boundary::Open : pressure::Boundary::Periodic);
  }
  return gs;
}

FluidSolver::FluidSolver(const MacGrid& g, FluidParams params, std::unique_ptr<pressure::PressureSolver> ps)
    : g_(g), params_(std::move(params)), ps_(std::move(ps)) {
  g_.validate();
  params_.validate();
  if (!ps_) throw Error("fluid: no pressure solver given");
  serial_sync_ = std::make_unique<SerialSync>(g_, params_.bc);
  sync_ = serial_sync_.get();
  for (int d = 0; d < 3; ++d) {
    E_old_[d] = make_face_field(g_, d, 1.0);
    E_new_[d] = make_face_field(g_, d, 1.0);
    R0_[d] = make_face_field(g_, d);
    R1_[d] = make_face_field(g_, d);
    ustar_[d] = make_face_field(g_, d);
    u1_[d] = make_face_field(g_, d);
  }
  p1_ = make_cell_field(g_);
  rhs_.assign(g_.cells(), 0.0);
  phi_.assign(g_.cells(), 0.0);
}

void FluidSolver::face_eps(const Field& eps_cell, Faces& E) const {
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> e = E[d].extent();
    const std::array<int, 3> dd = unit(d);
    const long st = eps_cell.stride(d);
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = -kGhost; k < e[2] + kGhost; ++k)
      for (int j = -kGhost; j < e[1] + kGhost; ++j) {
        const double* ec = eps_cell.data() + eps_cell.index(0, j, k);
        double* out = E[d].data() + E[d].index(0, j, k);
        for (int i = -kGhost; i < e[0] + kGhost; ++i) {
          int im = i - dd[0], jm = j - dd[1], km = k - dd[2];
          bool inside = im >= -kGhost && jm >= -kGhost && km >= -kGhost && i < g_.nx + kGhost &&
                        j < g_.ny + kGhost && k < g_.nz + kGhost;
          out[i] = inside ? 0.5 * (ec[i] + ec[i - st]) : 1.0;
        }
      }
  }
}

// R = -div(E rho u u) + div(eps tau) + E rho g + f_explicit on the active faces.
void FluidSolver::explicit_rhs(const Vel& v, const Field& eps_cell, const Faces& E, const Sources& src, Faces& R) {
  const std::array<const Field*, 3> vel{v[0], v[1], v[2]};
  const std::array<const Field*, 3> ef{&E[0], &E[1], &E[2]};
  for (int d = 0; d < 3; ++d) {
    FaceRange r = active_range(g_, params_.bc, d);
    const Field& fe = src.f_explicit[d];
    Field& Rd = R[d];
    const RowSpans* spans = spans_of(d);
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = -kGhost; k < Rd.nk() + kGhost; ++k)
      for (int j = -kGhost; j < Rd.nj() + kGhost; ++j) {
        double* out = Rd.data() + Rd.index(-kGhost, j, k);
        const int n = Rd.ni() + 2 * kGhost;
        const bool row = k >= r[2][0] && k < r[2][1] && j >= r[1][0] && j < r[1][1];
        if (!row) {
          std::fill(out, out + n, 0.0);
          continue;
        }
        // With spans, R is read (by the predictor) on the spans alone.
        const auto [i_lo, i_hi] = row_span(spans, r, j, k);
        const int q0 = spans ? i_lo + kGhost : 0, q1 = spans ? i_hi + kGhost : n;
        const double* e = E[d].data() + E[d].index(-kGhost, j, k);
        const double* f = fe.empty() ? nullptr : fe.data() + fe.index(-kGhost, j, k);
        for (int q = q0; q < q1; ++q) {
          const int i = q - kGhost;
          const bool active = i >= i_lo && i < i_hi;
          out[q] = active ? e[q] * params_.rho * params_.gravity[d] + (f ? f[q] : 0.0)  // eq. (13) eps rho g
                          : 0.0;
        }
      }
    add_momentum_terms(g_, d, true, params_.advection, params_.rho, params_.mu, vel, ef, eps_cell, r, R[d],
                       spans);
  }
}

// (E^{n+1} rho/dt + K) u_hat = E^n rho u^n/dt + R + K v_p, then the direct forcing, with
// R = R0 (Euler) or (R0 + R1)/2 (Heun, R1 != nullptr). Only the active faces are written: the
// ghost fill sets every other face (prescribed normal velocity, periodic image, ghosts).
void FluidSolver::predict(const FluidState& s, const Faces& R0, const Faces* R1, const Sources& src, double dt,
                          Faces& ustar) {
  const double rho = params_.rho;
  for (int d = 0; d < 3; ++d) {
    FaceRange r = active_range(g_, params_.bc, d);
    const Field &al = ibm_.alpha_face[d], &ub = ibm_.ub_face[d], &u = s.vel(d);
    const Field &K = src.K[d], &Kv = src.Kv[d];
    const RowSpans* spans = spans_of(d);
    // All face fields of component d share one layout: one offset per row serves them all.
#pragma omp parallel if (g_.cells() > kOmpMinWork)
    {
      const auto [ka, kb] =
          plane_chunk(spans, r[2][0], r[2][1] - r[2][0], omp_get_thread_num(), omp_get_num_threads());
      for (int k = ka; k < kb; ++k)
        for (int j = r[1][0]; j < r[1][1]; ++j) {
          const long o = u.index(0, j, k);
          const auto [i_lo, i_hi] = row_span(spans, r, j, k);
          if (spans) {  // alpha = 1 outside the span: u* = U_B
            const double* b = ub.data() + o;
            std::copy(b + r[0][0], b + i_lo, ustar[d].data() + o + r[0][0]);
            std::copy(b + i_hi, b + r[0][1], ustar[d].data() + o + i_hi);
          }
          const double *ur = u.data() + o, *eo = E_old_[d].data() + o, *en = E_new_[d].data() + o;
          const double *r0 = R0[d].data() + o, *r1 = R1 ? (*R1)[d].data() + o : nullptr;
          const double *kr = K.empty() ? nullptr : K.data() + o, *kv = Kv.empty() ? nullptr : Kv.data() + o;
          const double *ar = al.data() + o, *br = ub.data() + o;
          double* out = ustar[d].data() + o;
          for (int i = i_lo; i < i_hi; ++i) {
            const double Kf = kr ? kr[i] : 0.0;
            const double Rf = r1 ? 0.5 * (r0[i] + r1[i]) : r0[i];
            const double num = eo[i] * rho * ur[i] / dt + Rf + (kv ? kv[i] : 0.0);
            const double u_hat = num / (en[i] * rho / dt + Kf);  // eq. (13), K implicit
            const double a = ar[i];
            out[i] = (1 - a) * u_hat + a * br[i];  // eqs. (18), (20)
          }
        }
    }
    sync_->fill_velocity_component(d, ustar[d]);  // periodic images, wall faces, cut faces
  }
}

// Refuses a state of another grid, sources of another layout and eps outside (0, 1] (the
// first bad cell is named).
void FluidSolver::check_inputs(const FluidState& s, const Sources& src, double dt) {
  if (!(dt > 0)) throw Error(fmt::format("fluid: time step must be > 0 (got {})", dt));
  if (s.u.extent() != g_.face_extent(0) || s.p.extent() != g_.n() || s.eps_old.extent() != g_.n())
    throw Error("fluid: state does not match the solver's grid");
  for (int d = 0; d < 3; ++d) {
    check_source(src.K[d], g_, d, "K");
    check_source(src.Kv[d], g_, d, "Kv");
    check_source(src.f_explicit[d], g_, d, "f_explicit");
  }
  if (!src.mass.empty() && src.mass.extent() != g_.n()) throw Error("fluid: source 'mass' does not match the cells");
  auto t = timers_.scope("checks");
  auto ok = [&](int i, int j, int k) {
    return s.eps(i, j, k) > 0 && s.eps(i, j, k) <= 1 && s.eps_old(i, j, k) > 0 && s.eps_old(i, j, k) <= 1;
  };
  bool all_ok = true;
#pragma omp parallel for schedule(static) reduction(&& : all_ok) if (g_.cells() > kOmpMinWork)
  for (int k = 0; k < g_.nz; ++k)
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) all_ok = all_ok && ok(i, j, k);
  if (!sync_->any(!all_ok)) return;
  std::string bad;  // name the first bad cell
  for (int k = 0; k < g_.nz && bad.empty(); ++k)
    for (int j = 0; j < g_.ny && bad.empty(); ++j)
      for (int i = 0; i < g_.nx && bad.empty(); ++i)
        if (!ok(i, j, k)) {
          const Vec3 x = g_.cell_centre(i, j, k);
          bad = fmt::format("fluid: eps outside (0, 1] in cell ({}, {}, {}) at [{:.4g}, {:.4g}, {:.4g}] m", i, j, k,
                            x.x, x.y, x.z);
        }
  sync_->raise_if(!bad.empty(), bad);
}

// The divergence residuals and the Courant number of the state after a step.
void FluidSolver::step_statistics(const FluidState& s, const Sources& src, double dt, StepStats& st) const {
  const Divergence dv = divergence(s, src.mass, dt);
  st.max_divergence = dv.fluid;
  st.max_divergence_walls = dv.walls;
  double umax_d[3];
  for (int d = 0; d < 3; ++d) {
    double m = 0;
    const Field& f = s.vel(d);
#pragma omp parallel for schedule(static) reduction(max : m) if (g_.cells() > kOmpMinWork)
    for (int k = 0; k < f.nk(); ++k)
      for (int j = 0; j < f.nj(); ++j)
        for (int i = 0; i < f.ni(); ++i) m = std::max(m, std::fabs(f(i, j, k)));
    umax_d[d] = m;
  }
  sync_->max(umax_d, 3);
  double umax = 0;
  for (int d = 0; d < 3; ++d) umax += umax_d[d];
  st.cfl = umax * dt / g_.dx;
}

bool FluidSolver::update_walls(const geometry::Scene::Frame& frame) {
  if (!update_ibm(g_, frame, params_.ibm_samples, ibm_)) return false;
  sync_->copy_ghosts(ibm_.alpha_cell, kCells);
  for (int d = 0; d < 3; ++d) sync_->copy_ghosts(ibm_.alpha_face[d], d);
  ibm_.any_solid = sync_->any(ibm_.any_solid);
  mark_open_spans();
  return true;
}

void FluidSolver::mark_open_spans() {
  for (int d = 0; d < 3; ++d) {
    const FaceRange r = active_range(g_, params_.bc, d);
    const long nj = r[1][1] - r[1][0], nk = std::max(0, r[2][1] - r[2][0]), rows = std::max(0L, nj * nk);
    span_lo_[d].assign(static_cast<size_t>(rows), r[0][0]);
    span_hi_[d].assign(static_cast<size_t>(rows), r[0][1]);
    if (ibm_.any_solid) {
      const Field &al = ibm_.alpha_face[d], &ub = ibm_.ub_face[d];
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
      for (long q = 0; q < rows; ++q) {
        const int j = r[1][0] + static_cast<int>(q % nj), k = r[2][0] + static_cast<int>(q / nj);
        const double *a = al.data() + al.index(0, j, k), *b = ub.data() + ub.index(0, j, k);
        auto inside = [&](int i) { return a[i] == 1.0 && !(b[i] == 0 && std::signbit(b[i])); };
        int lo = r[0][0], hi = r[0][1];
        while (lo < hi && inside(lo)) ++lo;
        while (hi > lo && inside(hi - 1)) --hi;
        span_lo_[d][q] = lo, span_hi_[d][q] = lo < hi ? hi : lo;
      }
    }
    span_work_[d].assign(static_cast<size_t>(nk) + 1, 0);  // the work per plane, summed
    for (long k = 0; k < nk; ++k) {
      long w = 0;
      for (long j = 0; j < nj; ++j) {
        const long open = span_hi_[d][j + nj * k] - span_lo_[d][j + nj * k];
        w += open + (r[0][1] - r[0][0] - open) / kCopyShare + kRowWork;
      }
      span_work_[d][k + 1] = span_work_[d][k] + w;
    }
    spans_[d] = {span_lo_[d].data(), span_hi_[d].data(), span_work_[d].data()};
  }
}

const RowSpans* FluidSolver::spans_of(int d) const {
  return skip_walls_ && !span_lo_[d].empty() ? &spans_[d] : nullptr;
}

long FluidSolver::faces_in_walls(int d) const {
  const FaceRange r = active_range(g_, params_.bc, d);
  long n = 0;
  for (size_t q = 0; q < span_lo_[d].size(); ++q) n += (r[0][1] - r[0][0]) - (span_hi_[d][q] - span_lo_[d][q]);
  return n;
}

// The step of fluid_solver.hpp: IBM fractions at t^{n+1}, explicit terms, predictor,
// projection; for time_order 2 a projected stage 1 and the Heun average first.
StepStats FluidSolver::advance(FluidState& s, const geometry::Scene::Frame& frame_end, const Sources& src, double dt) {
  check_inputs(s, src, dt);
  StepStats st;
  {
    auto t = timers_.scope("ibm");
    st.ibm_updated = update_walls(frame_end);
  }
  const Vel vel{&s.u, &s.v, &s.w};
  {
    auto t = timers_.scope("ghosts, face eps");
    sync_->fill_scalar(s.eps, ScalarKind::ZeroGradient);
    sync_->fill_scalar(s.eps_old, ScalarKind::ZeroGradient);
    face_eps(s.eps_old, E_old_);
    face_eps(s.eps, E_new_);
    sync_->fill_velocity(s.u, s.v, s.w);
  }
  {
    auto t = timers_.scope("advection+viscous");
    explicit_rhs(vel, s.eps_old, E_old_, src, R0_);
  }
  {
    auto t = timers_.scope("predictor update");
    predict(s, R0_, nullptr, src, dt, ustar_);
  }
  set_pressure_coefficients(src, dt);
  if (params_.time_order == 2) {
    // Stage 1 result u^(1) (projected), then the Heun average of the explicit terms.
    p1_ = s.p;
    const Vel v1{&u1_[0], &u1_[1], &u1_[2]};
    const bool loose = params_.stage_rel_tol > 0 && params_.stage_rel_tol != params_.pressure.rel_tol;
    if (loose) ps_->set_rel_tol(params_.stage_rel_tol);
    project(s, src, dt, ustar_, v1, p1_, st);
    if (loose) ps_->set_rel_tol(params_.pressure.rel_tol);
    st.stage_iterations = st.pressure_iterations;
    {
      auto t = timers_.scope("advection+viscous");
      explicit_rhs(v1, s.eps, E_new_, src, R1_);
    }
    auto t = timers_.scope("predictor update");
    std::swap(s.p, p1_);  // initial guess
    predict(s, R0_, &R1_, src, dt, ustar_);  // Heun: R = (R0 + R1)/2
  }
  project(s, src, dt, ustar_, vel, s.p, st);
  {
    auto t = timers_.scope("diagnostics");
    step_statistics(s, src, dt, st);
  }
  s.eps_old = s.eps;
  s.t += dt;
  return st;
}

FluidSolver::Divergence FluidSolver::divergence(const FluidState& s, const Field& mass, double dt) const {
  // E on a face is the mean of its two cells (ghost cells of eps filled by advance()).
  auto flux = [&](int d, int i, int j, int k) {
    std::array<int, 3> e = unit(d);
    return 0.5 * (s.eps(i, j, k) + s.eps(i - e[0], j - e[1], k - e[2])) * s.vel(d)(i, j, k);
  };
  // Cells entirely inside walls (alpha_cell = 1) have no pressure unknown: nothing imposes
  // continuity there (their faces carry the wall velocity while eps may vary), so they are
  // reported apart.
  const bool have_alpha = ibm_.alpha_cell.ni() == g_.nx && ibm_.alpha_cell.nj() == g_.ny && ibm_.alpha_cell.nk() == g_.nz;
  double m_fluid = 0, m_wall = 0;
#pragma omp parallel for schedule(static) reduction(max : m_fluid, m_wall) if (g_.cells() > kOmpMinWork)
  for (int k = 0; k < g_.nz; ++k)
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) {
        double div = (s.eps(i, j, k) - s.eps_old(i, j, k)) / dt;
        if (!mass.empty()) div += mass(i, j, k);
        for (int d = 0; d < 3; ++d) {
          std::array<int, 3> e = unit(d);
          div += (flux(d, i + e[0], j + e[1], k + e[2]) - flux(d, i, j, k)) / g_.dx;
        }
        if (have_alpha && ibm_.alpha_cell(i, j, k) >= 1.0)
          m_wall = std::max(m_wall, std::fabs(div));
        else
          m_fluid = std::max(m_fluid, std::fabs(div));
      }
  double m[2] = {m_fluid, m_wall};
  sync_->max(m, 2);
  return {m[0], m[1]};
}

double FluidSolver::stable_dt(const FluidState& s) const {
  double m[4] = {0, 0, 0, 0};  // max |u_d| per component, then the fastest wall side
  for (int d = 0; d < 3; ++d) {  // a maximum is exact: the same for any split between threads
    const Field& f = s.vel(d);
    double md = 0;
#pragma omp parallel for schedule(static) reduction(max : md) if (long(f.ni()) * f.nj() * f.nk() > kOmpMinWork)
    for (int k = 0; k < f.nk(); ++k)
      for (int j = 0; j < f.nj(); ++j) {
        const double* row = f.data() + f.index(0, j, k);
        for (int i = 0; i < f.ni(); ++i) md = std::max(md, std::fabs(row[i]));
      }
    m[d] = md;
  }
  for (const auto& sb : params_.bc)
    if (sb.type == BcType::Wall) m[3] = std::max(m[3], norm(sb.wall_velocity));
  sync_->max(m, 4);
  double umax = 0;
  for (int d = 0; d < 3; ++d) umax += m[d];
  umax = std::max(umax, m[3]);
  double dt = params_.dt_max;
  if (umax > 0) dt = std::min(dt, params_.cfl * g_.dx / umax);
  if (params_.mu > 0) dt = std::min(dt, params_.visc_safety * g_.dx * g_.dx * params_.rho / (6 * params_.mu));
  return dt;
}

}  // namespace cgdem::fluid
