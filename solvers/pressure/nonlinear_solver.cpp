// KINSOL Newton-Krylov solve of div(a(grad phi) grad phi) = rhs; see nonlinear_solver.hpp.
#include "solvers/pressure/nonlinear_solver.hpp"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spfgmr.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/timers.hpp"
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

void NonlinearPressureSolver::face_gradients(const GridSpec& g, const double* phi, FaceFields& grad) {
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  grad.x.resize(long(nx + 1) * ny * nz);
  grad.y.resize(long(nx) * (ny + 1) * nz);
  grad.z.resize(long(nx) * ny * (nz + 1));
  auto c = [&](int i, int j, int k) { return phi[i + long(nx) * (j + long(ny) * k)]; };
  // Face between lo and hi cell values at spacing h, or a boundary face of an axis.
  auto fg = [](int f, int n, Boundary blo, Boundary bhi, double lo, double hi, double first, double last,
               double h) {
    if (f > 0 && f < n) return (hi - lo) / h;
    if (blo == Boundary::Periodic) return (first - last) / h;
    if (f == 0) return blo == Boundary::Open ? 2 * first / h : 0.0;
    return bhi == Boundary::Open ? -2 * last / h : 0.0;
  };
#pragma omp parallel for collapse(2) schedule(static) if (g.cells() >= kParallelMin)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i)
        grad.x[i + long(nx + 1) * (j + long(ny) * k)] =
            fg(i, nx, g.bc[0], g.bc[1], c(std::max(i - 1, 0), j, k), c(std::min(i, nx - 1), j, k), c(0, j, k),
               c(nx - 1, j, k), g.dx);
#pragma omp parallel for collapse(2) schedule(static) if (g.cells() >= kParallelMin)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i)
        grad.y[i + long(nx) * (j + long(ny + 1) * k)] =
            fg(j, ny, g.bc[2], g.bc[3], c(i, std::max(j - 1, 0), k), c(i, std::min(j, ny - 1), k), c(i, 0, k),
               c(i, ny - 1, k), g.dy);
#pragma omp parallel for collapse(2) schedule(static) if (g.cells() >= kParallelMin)
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        grad.z[i + long(nx) * (j + long(ny) * k)] =
            fg(k, nz, g.bc[4], g.bc[5], c(i, j, std::max(k - 1, 0)), c(i, j, std::min(k, nz - 1)), c(i, j, 0),
               c(i, j, nz - 1), g.dz);
}

struct NonlinearPressureSolver::Impl {
  GridSpec g;
  double ftol = 1e-8, inner_tol = 1e-3;
  int max_newton = 50;
  SUNContext ctx = nullptr;
  void* kin = nullptr;
  N_Vector u = nullptr, ones = nullptr;
  SUNLinearSolver ls = nullptr;
  Poisson7 op;
  std::unique_ptr<PressureSolver> inner;
  FaceFields grad, a;
  const CoefFn* coef = nullptr;
  const std::vector<double>* rhs = nullptr;
  std::vector<double> v_rhs, z;
  explicit Impl(const GridSpec& grid) : g(grid), op(grid) {}

  void coefficients_at(const double* phi) {
    face_gradients(g, phi, grad);
    a.x.assign(grad.x.size(), 0.0);
    a.y.assign(grad.y.size(), 0.0);
    a.z.assign(grad.z.size(), 0.0);
    (*coef)(grad, a);
  }
  // F(phi) = A(a(g(phi))) phi + rhs
  static int func(N_Vector uu, N_Vector ff, void* self) {
    auto* m = static_cast<Impl*>(self);
    const double* phi = N_VGetArrayPointer_Serial(uu);
    double* f = N_VGetArrayPointer_Serial(ff);
    m->coefficients_at(phi);
    m->op.set(m->a.x, m->a.y, m->a.z);
    m->op.apply(phi, f);
    const long n = m->g.cells();
    for (long c = 0; c < n; ++c) f[c] += (*m->rhs)[c];
    return 0;
  }
  // Picard preconditioner: freeze a at the current iterate.
  static int psetup(N_Vector uu, N_Vector, N_Vector, N_Vector, void* self) {
    auto* m = static_cast<Impl*>(self);
    m->coefficients_at(N_VGetArrayPointer_Serial(uu));
    m->inner->set_coefficients(m->a.x, m->a.y, m->a.z);
    return 0;
  }
  // v <- A(a_k)^{-1} v, i.e. the inner solve of div(a_k grad z) = -v.
  static int psolve(N_Vector, N_Vector, N_Vector, N_Vector, N_Vector vv, void* self) {
    auto* m = static_cast<Impl*>(self);
    double* v = N_VGetArrayPointer_Serial(vv);
    const long n = m->g.cells();
    m->v_rhs.resize(n);
    for (long c = 0; c < n; ++c) m->v_rhs[c] = -v[c];
    m->z.assign(n, 0.0);
    m->inner->solve(m->v_rhs, m->z);
    std::copy(m->z.begin(), m->z.end(), v);
    return 0;
  }
};

NonlinearPressureSolver::NonlinearPressureSolver(const GridSpec& g, const SolverOptions& inner, double ftol,
                                                 int max_newton, double inner_rel_tol)
    : impl_(std::make_unique<Impl>(g)) {
  auto& m = *impl_;
  if (!(ftol > 0) || max_newton < 1 || !(inner_rel_tol > 0))
    throw Error("pressure: nonlinear solve needs ftol > 0, max_newton >= 1, inner_rel_tol > 0");
  m.ftol = ftol;
  m.max_newton = max_newton;
  SolverOptions in = inner;
  in.rel_tol = inner_rel_tol;
  m.inner = make_pressure_solver(g, in);
  if (SUNContext_Create(nullptr, &m.ctx) != 0) throw Error("pressure: SUNContext_Create failed");
  const long n = g.cells();
  m.u = N_VNew_Serial(n, m.ctx);
  m.ones = N_VNew_Serial(n, m.ctx);
  N_VConst(1.0, m.ones);
  m.kin = KINCreate(m.ctx);
  if (!m.kin || KINInit(m.kin, Impl::func, m.u) != KIN_SUCCESS) throw Error("pressure: KINInit failed");
  KINSetUserData(m.kin, impl_.get());
  m.ls = SUNLinSol_SPFGMR(m.u, SUN_PREC_RIGHT, 30, m.ctx);
  KINSetLinearSolver(m.kin, m.ls, nullptr);
  KINSetPreconditioner(m.kin, Impl::psetup, Impl::psolve);
  KINSetMaxSetupCalls(m.kin, 1);  // refreeze the coefficient at every Newton iterate
  KINSetNumMaxIters(m.kin, max_newton);
  KINSetMaxNewtonStep(m.kin, 1e30);  // the default 1000 ||u0|| is 0 for u0 = 0
  KINSetScaledStepTol(m.kin, 1e-15);
}

NonlinearPressureSolver::~NonlinearPressureSolver() {
  auto& m = *impl_;
  KINFree(&m.kin);
  SUNLinSolFree(m.ls);
  N_VDestroy(m.u);
  N_VDestroy(m.ones);
  SUNContext_Free(&m.ctx);
}

NonlinearStats NonlinearPressureSolver::solve_nonlinear(const CoefFn& coef_fn, const std::vector<double>& rhs,
                                                        std::vector<double>& phi) {
  auto& m = *impl_;
  const long n = m.g.cells();
  if (long(rhs.size()) != n || long(phi.size()) != n)
    throw Error("pressure: solve_nonlinear needs rhs and phi of " + std::to_string(n) + " cells");
  if (!coef_fn) throw Error("pressure: solve_nonlinear needs a coefficient function");
  Stopwatch sw;
  m.coef = &coef_fn;
  m.rhs = &rhs;
  double rmax = 0;
  for (double v : rhs) rmax = std::max(rmax, std::abs(v));
  NonlinearStats st;
  if (rmax == 0) rmax = 1;
  KINSetFuncNormTol(m.kin, m.ftol * rmax);
  std::copy(phi.begin(), phi.end(), N_VGetArrayPointer_Serial(m.u));
  const int flag = KINSol(m.kin, m.u, KIN_LINESEARCH, m.ones, m.ones);
  std::copy(N_VGetArrayPointer_Serial(m.u), N_VGetArrayPointer_Serial(m.u) + n, phi.begin());
  long nni = 0, nli = 0;
  KINGetNumNonlinSolvIters(m.kin, &nni);
  KINGetNumLinIters(m.kin, &nli);
  // True residual at the returned phi.
  std::vector<double> f(n);
  N_Vector fv = N_VMake_Serial(n, f.data(), m.ctx);
  Impl::func(m.u, fv, impl_.get());
  N_VDestroy(fv);
  double fmax = 0;
  for (double v : f) fmax = std::max(fmax, std::abs(v));
  st.newton_iterations = int(nni);
  st.linear_iterations = nli;
  st.rel_fnorm = fmax / rmax;
  st.converged = flag >= 0 && st.rel_fnorm <= m.ftol;
  st.seconds = sw.seconds();
  return st;
}

}  // namespace cgdem::pressure
