// FluidSolver::project: the pressure equation and the velocity correction (eq. 12).
//
//   a_f   = (1 - alpha_f) E_f^2 / (E_f rho/dt + K_f)                   (face coefficient)
//   div(a grad p)_c = sum_d [ (E u*)_{c+d} - (E u*)_c ]/dx + (eps_c^{n+1} - eps_c^n)/dt
//   u_f   = u*_f - (a_f / E_f) (p_c - p_{c-d}) / dx                    (active faces)
//
// Open sides hold p = p_open on the boundary face: the pressure solver's Open row assumes
// the ghost -p_c, so the known part 2 a_f p_open / dx^2 is moved to the right-hand side.
// Wall boundary faces keep their prescribed normal velocity (coefficient 0).
#include <fmt/format.h>

#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem::fluid {

namespace {

double value_or_zero(const Field& f, int i, int j, int k) { return f.empty() ? 0.0 : f(i, j, k); }

}  // namespace

// a_f on every face in the layout of pressure_solver.hpp; handed to the pressure solver only
// when they changed (its set-up, e.g. the multigrid hierarchy, is the expensive part).
void FluidSolver::set_pressure_coefficients(const Sources& src, double dt) {
  auto t = timers_.scope("pressure coefficients");
  const double rho = params_.rho;
  std::array<std::vector<double>*, 3> coef{&ax_, &ay_, &az_};
  bool changed = !coeffs_set_;
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> e = g_.face_extent(d);
    std::vector<double>& next = next_[d];
    next.resize(static_cast<size_t>(e[0]) * e[1] * e[2]);
    const BcType lo = params_.bc[2 * d].type, hi = params_.bc[2 * d + 1].type;
    bool diff = false;
    const std::vector<double>& cur = *coef[d];
    const bool have = cur.size() == next.size();
#pragma omp parallel for schedule(static) reduction(|| : diff) if (g_.cells() > kOmpMinWork)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          const long q = i + static_cast<long>(e[0]) * (j + static_cast<long>(e[1]) * k);
          int f = d == 0 ? i : (d == 1 ? j : k);
          double a = 0.0;
          if (!((f == 0 && lo == BcType::Wall) || (f == e[d] - 1 && hi == BcType::Wall))) {
            double E = E_new_[d](i, j, k), K = value_or_zero(src.K[d], i, j, k);
            a = (1 - ibm_.alpha_face[d](i, j, k)) * E * E / (E * rho / dt + K);
          }
          next[q] = a;
          diff = diff || !have || !(a == cur[q]);
        }
    changed = changed || diff;
  }
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
  const double rho = params_.rho, dx = g_.dx;
  std::array<std::vector<double>*, 3> coef{&ax_, &ay_, &az_};
  {
    auto t = timers_.scope("pressure rhs");
    // Right-hand side div(E u*) + d(eps)/dt, with the Open-side boundary values.
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::array<int, 3> c{i, j, k};
          double r = (s.eps(i, j, k) - s.eps_old(i, j, k)) / dt;
          for (int d = 0; d < 3; ++d) {
            std::array<int, 3> e = unit(d);
            r += (E_new_[d](i + e[0], j + e[1], k + e[2]) * ustar[d](i + e[0], j + e[1], k + e[2]) -
                  E_new_[d](i, j, k) * ustar[d](i, j, k)) /
                 dx;
            std::array<int, 3> fe = g_.face_extent(d);
            for (int h = 0; h < 2; ++h) {
              const SideBc& sb = params_.bc[2 * d + h];
              if (sb.type != BcType::Open || c[d] != (h == 0 ? 0 : g_.n()[d] - 1)) continue;
              std::array<int, 3> f = c;
              f[d] += h;
              double a = (*coef[d])[f[0] + static_cast<long>(fe[0]) * (f[1] + static_cast<long>(fe[1]) * f[2])];
              r -= 2 * a * sb.pressure / (dx * dx);
            }
          }
          const long q = i + static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
          rhs_[q] = r;
          phi_[q] = p(i, j, k);
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
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p(i, j, k) = phi_[i + static_cast<long>(nx) * (j + static_cast<long>(ny) * k)];
  fill_scalar_ghosts(g_, params_.bc, p, ScalarKind::Pressure);
  for (int d = 0; d < 3; ++d) {
    Field& u = *vel[d];
    u = ustar[d];
    std::array<int, 3> e = unit(d);
    std::array<int, 2> r = active_face_range(g_, params_.bc, d);
    std::array<int, 3> lo{0, 0, 0}, hi = g_.n();
    lo[d] = r[0], hi[d] = r[1];
#pragma omp parallel for schedule(static) if (g_.cells() > kOmpMinWork)
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i) {
          double E = E_new_[d](i, j, k), K = value_or_zero(src.K[d], i, j, k);
          double c = (1 - ibm_.alpha_face[d](i, j, k)) * E / (E * rho / dt + K);
          u(i, j, k) -= c * (p(i, j, k) - p(i - e[0], j - e[1], k - e[2])) / dx;
        }
  }
  fill_velocity_ghosts(g_, params_.bc, *vel[0], *vel[1], *vel[2]);
}

}  // namespace cgdem::fluid
