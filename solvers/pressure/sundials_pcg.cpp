// SUNLinSol_PCG driver with deterministic OpenMP vector operations; see sundials_pcg.hpp.
#include "solvers/pressure/sundials_pcg.hpp"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_pcg.h>

#include "core/error.hpp"
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

namespace {
double* data(N_Vector v) { return N_VGetArrayPointer_Serial(v); }
long len(N_Vector v) { return N_VGetLength_Serial(v); }

realtype op_dot(N_Vector a, N_Vector b) { return dot(data(a), data(b), len(a)); }
void op_linearsum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const long n = len(z);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}
void op_scale(realtype a, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const long n = len(z);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long i = 0; i < n; ++i) zd[i] = a * xd[i];
}
void op_prod(N_Vector x, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const long n = len(z);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}
void op_const(realtype c, N_Vector z) {
  double* zd = data(z);
  const long n = len(z);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long i = 0; i < n; ++i) zd[i] = c;
}
void install_ops(N_Vector v) {
  v->ops->nvdotprod = op_dot;
  v->ops->nvlinearsum = op_linearsum;
  v->ops->nvscale = op_scale;
  v->ops->nvprod = op_prod;
  v->ops->nvconst = op_const;
}
}  // namespace

struct SundialsPcg::Impl {
  SUNContext ctx = nullptr;
  N_Vector xv = nullptr, bv = nullptr;
  SUNLinearSolver ls = nullptr;
  Apply op, prec;
  long n = 0;

  static int atimes(void* self, N_Vector v, N_Vector z) {
    auto* me = static_cast<Impl*>(self);
    me->op(data(v), data(z));
    return 0;
  }
  static int psolve(void* self, N_Vector r, N_Vector z, realtype, int) {
    auto* me = static_cast<Impl*>(self);
    me->prec(data(r), data(z));
    return 0;
  }
};

SundialsPcg::SundialsPcg(long n, Apply op, Apply prec) : impl_(new Impl) {
  auto& m = *impl_;
  m.n = n;
  m.op = std::move(op);
  m.prec = std::move(prec);
  if (SUNContext_Create(nullptr, &m.ctx) != 0) throw Error("pressure: SUNContext_Create failed");
  m.xv = N_VMake_Serial(n, nullptr, m.ctx);
  m.bv = N_VMake_Serial(n, nullptr, m.ctx);
  install_ops(m.xv);
  install_ops(m.bv);
  const int pretype = m.prec ? SUN_PREC_LEFT : SUN_PREC_NONE;
  // PCG clones its work vectors from a template that owns its data; the clones keep our ops.
  N_Vector tmpl = N_VNew_Serial(n, m.ctx);
  install_ops(tmpl);
  m.ls = SUNLinSol_PCG(tmpl, pretype, 100, m.ctx);
  N_VDestroy(tmpl);
  if (!m.ls) throw Error("pressure: SUNLinSol_PCG failed");
  SUNLinSolSetATimes(m.ls, impl_, Impl::atimes);
  if (m.prec) SUNLinSolSetPreconditioner(m.ls, impl_, nullptr, Impl::psolve);
  if (SUNLinSolInitialize(m.ls) != 0) throw Error("pressure: SUNLinSolInitialize (PCG) failed");
}

SundialsPcg::~SundialsPcg() {
  SUNLinSolFree(impl_->ls);
  N_VDestroy(impl_->xv);
  N_VDestroy(impl_->bv);
  SUNContext_Free(&impl_->ctx);
  delete impl_;
}

SundialsPcg::Result SundialsPcg::solve(const double* b, double* x, double abs_tol, int max_iter,
                                       bool zero_guess) {
  auto& m = *impl_;
  N_VSetArrayPointer_Serial(const_cast<double*>(b), m.bv);
  N_VSetArrayPointer_Serial(x, m.xv);
  SUNLinSol_PCGSetMaxl(m.ls, max_iter);
  SUNLinSolSetZeroGuess(m.ls, zero_guess ? SUNTRUE : SUNFALSE);
  const int flag = SUNLinSolSolve(m.ls, nullptr, m.xv, m.bv, abs_tol);
  Result r;
  r.iterations = SUNLinSolNumIters(m.ls);
  r.res_norm = SUNLinSolResNorm(m.ls);
  r.converged = (flag == SUNLS_SUCCESS);
  if (flag < 0) throw Error("pressure: SUNLinSol_PCG failed with flag " + std::to_string(flag));
  return r;
}

}  // namespace cgdem::pressure
