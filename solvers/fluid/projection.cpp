// FluidSolver::project: the pressure equation and the velocity correction (eq. 12).
//
//   a_f   = (1 - alpha_f) E_f^2 / (E_f rho/dt + K_f)                   (face coefficient)
//   div(a grad p)_c = sum_d [ (E u*)_{c+d} - (E u*)_c ]/dx + (eps_c^{n+1} - eps_c^n)/dt + mass_c
//   u_f   = u*_f - (a_f / E_f) (p_c - p_{c-d}) / dx                    (active faces)
//
// Open sides hold p = p_open on the boundary face: the pressure solver's Open row assumes
// the ghost -p_c, so the known part 2 a_f p_open / dx^2 is moved to the right-hand side.
// Wall boundary faces keep their prescribed normal velocity (coefficient 0).
#include <fmt/format.h>

#include <optional>

#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem::fluid {

// a_f on every face in the layout of pressure_solver.hpp; handed to the pressure solver only
// when they changed (its set-up, e.g. the multigrid hierarchy, is the expensive part). The
// correction factor c_f = (1 - alpha_f) E_f / (E_f rho/dt + K_f) = a_f / E_f is kept beside it
// (the same expression the correction evaluated face by face before).
void FluidSolver::set_pressure_coefficients(const Sources& src, double dt) {
  std::array<std::vector<double>*, 3> coef{&ax_, &ay_, &az_};
  bool changed = !coeffs_set_;
  std::optional<PhaseTimers::Scope> t(std::in_place, timers_, timers_.id("pressure coefficients"));
  const double rho = params_.rho;
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> e = g_.face_extent(d);
    std::vector<double>& next = next_[d];
    next.resize(static_cast<size_t>(e[0]) * e[1] * e[2]);
    corr_[d].resize(next.size());
    const BcType lo = params_.bc[2 * d].type, hi = params_.bc[2 * d + 1].type;
    bool diff = false;
    const std::vector<double>& cur = *coef[d];
    const bool have = cur.size() == next.size();
    const Field &E = E_new_[d], &al = ibm_.alpha_face[d], &K = src.K[d];
#pragma omp parallel for schedule(static) reduction(|| : diff) if (g_.cells() > kOmpMinWork)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j) {
        const long q0 = static_cast<long>(e[0]) * (j + static_cast<long>(e[1]) * k), o = E.index(0, j, k);
        const double *er = E.data() + o, *ar = al.data() + o, *kr = K.empty() ? nullptr : K.data() + o;
        double *nr = next.data() + q0, *cr = corr_[d].data() + q0;
        const double* cu = have ? cur.data() + q0 : nullptr;
        const int f = d == 1 ? j : k;  // the face index along d for d = 1, 2 (per row)
        const bool row_wall = d > 0 && ((f == 0 && lo == BcType::Wall) || (f == e[d] - 1 && hi == BcType::Wall));
        bool rd = false;
        for (int i = 0; i < e[0]; ++i) {
          const bool wall = row_wall || (d == 0 && ((i == 0 && lo == BcType::Wall) || (i == e[0] - 1 && hi == BcType::Wall)));
          double a = 0.0, c = 0.0;
          if (!wall) {
            const double Ef = er[i], Kf = kr ? kr[i] : 0.0;
            a = (1 - ar[i]) * Ef * Ef / (Ef * rho / dt + Kf);
            c = (1 - ar[i]) * Ef / (Ef * rho / dt + Kf);
          }
          nr[i] = a;
          cr[i] = c;
          rd = rd || !cu || !(a == cu[i]);
        }
        diff = diff || rd;
      }
    changed = changed || diff;
  }
  changed = sync_->any(changed);  // the set-up is collective over the ranks
  t.reset();  // the set-up is a phase of its own, not a part of this one
  if (changed) {
    for (int d = 0; d < 3; ++d) coef[d]->swap(next_[d]);
    auto ts = timers_.scope("pressure set-up");
    ps_->set_coefficients(ax_, ay_, az_);
    coeffs_set_ = true;
  }
}

void FluidSolver::project(const FluidState& s, const Sources& src, double dt, Faces& ustar, const Vel& vel, Field& p,
                          StepStats& st) {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const double dx = g_.dx;
  {
    auto t = timers_.scope("pressure rhs");
    // Right-hand side div(E u*) + d(eps)/dt, with the Open-side boundary values (added right
    // after the flux of their axis, as the terms of one cell are summed in that order).
    const SideBc* open[6];
    for (int q = 0; q < 6; ++q)  // a cut side (Open on a block) has no boundary pressure
      open[q] = params_.bc[q].type == BcType::Open && !sync_->is_cut(q) ? &params_.bc[q] : nullptr;
    const std::array<int, 3> n = g_.n();
    auto open_term = [&](int d, int h, int i, int j, int k) {
      std::array<int, 3> f{i, j, k};
      f[d] += h;
      const std::array<int, 3> fe = g_.face_extent(d);
      const std::vector<double>& cf = d == 0 ? ax_ : (d == 1 ? ay_ : az_);
      const double a = cf[f[0] + static_cast<long>(fe[0]) * (f[1] + static_cast<long>(fe[1]) * f[2])];
      return 2 * a * open[2 * d + h]->pressure / (dx * dx);
    };
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) {
        const long oc = s.eps.index(0, j, k);
        const double *en = s.eps.data() + oc, *eo = s.eps_old.data() + oc, *pr = p.data() + oc;
        const double* ms = src.mass.empty() ? nullptr : src.mass.data() + oc;
        const long ox = E_new_[0].index(0, j, k), oy = E_new_[1].index(0, j, k), oz = E_new_[2].index(0, j, k);
        const double *Ex = E_new_[0].data() + ox, *ux = ustar[0].data() + ox;
        const double *Ey = E_new_[1].data() + oy, *uy = ustar[1].data() + oy;
        const double *Ez = E_new_[2].data() + oz, *uz = ustar[2].data() + oz;
        const long sy = E_new_[1].stride(1), sz = E_new_[2].stride(2);
        const bool oyl = open[2] && j == 0, oyh = open[3] && j == n[1] - 1;
        const bool ozl = open[4] && k == 0, ozh = open[5] && k == n[2] - 1;
        const long q0 = static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
        for (int i = 0; i < nx; ++i) {
          double r = (en[i] - eo[i]) / dt;
          r += (Ex[i + 1] * ux[i + 1] - Ex[i] * ux[i]) / dx;
          if (open[0] && i == 0) r -= open_term(0, 0, i, j, k);
          if (open[1] && i == nx - 1) r -= open_term(0, 1, i, j, k);
          r += (Ey[i + sy] * uy[i + sy] - Ey[i] * uy[i]) / dx;
          if (oyl) r -= open_term(1, 0, i, j, k);
          if (oyh) r -= open_term(1, 1, i, j, k);
          r += (Ez[i + sz] * uz[i + sz] - Ez[i] * uz[i]) / dx;
          if (ozl) r -= open_term(2, 0, i, j, k);
          if (ozh) r -= open_term(2, 1, i, j, k);
          if (ms) r += ms[i];
          rhs_[q0 + i] = r;
          phi_[q0 + i] = pr[i];
        }
      }
  }
  {
    auto t = timers_.scope("pressure solve");
    pressure::SolveStats ss = ps_->solve(rhs_, phi_);
    st.pressure_iterations += ss.iterations;
    st.pressure_residual = ss.rel_residual;
    st.pressure_converged = st.pressure_converged && ss.converged;
  }
  auto t = timers_.scope("correction");
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      double* pr = p.data() + p.index(0, j, k);
      const double* src_row = phi_.data() + static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
      for (int i = 0; i < nx; ++i) pr[i] = src_row[i];
    }
  sync_->fill_scalar(p, ScalarKind::Pressure);
  // u = u* - c_f (p_c - p_{c-d})/dx on the active faces; the ghost fill sets the others.
  for (int d = 0; d < 3; ++d) {
    Field& u = *vel[d];
    const long sp = p.stride(d);
    std::array<int, 2> r = active_face_range(g_, params_.bc, d);
    std::array<int, 3> lo{0, 0, 0}, hi = g_.n();
    lo[d] = r[0], hi[d] = r[1];
    const std::array<int, 3> fe = g_.face_extent(d);
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j) {
        const long o = u.index(0, j, k);
        const double* us = ustar[d].data() + o;
        double* ur = u.data() + o;
        const double* pr = p.data() + p.index(0, j, k);
        const double* cr = corr_[d].data() + static_cast<long>(fe[0]) * (j + static_cast<long>(fe[1]) * k);
        for (int i = lo[0]; i < hi[0]; ++i) ur[i] = us[i] - cr[i] * (pr[i] - pr[i - sp]) / dx;
      }
  }
  sync_->fill_velocity(*vel[0], *vel[1], *vel[2]);
}

}  // namespace cgdem::fluid
