// SUNLinSol_PCG driver with deterministic OpenMP vector operations; see sundials_pcg.hpp.
#include "solvers/pressure/sundials_pcg.hpp"

#include <nvector/nvector_serial.h>
#include <omp.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_pcg.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/error.hpp"
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

namespace {
// The cells an operation visits: all (act == nullptr) or the segments of act.
struct Cells {
  const ActiveRows* act = nullptr;
  int nx = 0;
};

// A serial vector's content followed by the cells (the serial accessors read the first part).
struct Content {
  _N_VectorContent_Serial serial;
  const Cells* cells;
};

double* data(N_Vector v) { return N_VGetArrayPointer_Serial(v); }
long len(N_Vector v) { return N_VGetLength_Serial(v); }
const Cells& cells_of(N_Vector v) { return *static_cast<Content*>(v->content)->cells; }

// f(a, b) for every range [a, b) of cells visited, each thread its share of rows (segments)
// or an even share of the cells (all).
template <class F>
void for_cells(const Cells& cs, long n, F&& f) {
#pragma omp parallel if (n >= kParallelMin)
  {
    const int nth = omp_get_num_threads(), t = omp_get_thread_num();
    if (!cs.act) {
      f(n * t / nth, n * (t + 1) / nth);
    } else {
      int r0, r1;
      cs.act->share(t, nth, r0, r1);
      for (int r = r0; r < r1; ++r)
        for (int q = cs.act->begin(r); q < cs.act->end(r); ++q)
          f(long(cs.nx) * r + cs.act->lo(q), long(cs.nx) * r + cs.act->hi(q));
    }
  }
}

// The blocked dot product of poisson7.cpp's dot() (blocks of kDotBlock cells, summed in block
// order) over the segments: each block adds its visited cells in ascending order.
constexpr long kDotBlock = 4096;
double segment_dot(const Cells& cs, const double* a, const double* b, long n) {
  const ActiveRows& act = *cs.act;
  const long nx = cs.nx, nb = (n + kDotBlock - 1) / kDotBlock;
  std::vector<double> part(nb, 0.0);
#pragma omp parallel if (n >= kParallelMin)
  {
    const int nth = omp_get_num_threads(), t = omp_get_thread_num();
    // Blocks [B(t), B(t + 1)): the first block starting at or after the thread's first row.
    auto first_block = [&](int q) {
      int r0, r1;
      act.share(q, nth, r0, r1);
      return q >= nth ? nb : (long(r0) * nx + kDotBlock - 1) / kDotBlock;
    };
    const long b0 = first_block(t), b1 = first_block(t + 1);
    for (long blk = b0; blk < b1; ++blk) {
      const long lo = blk * kDotBlock, hi = std::min(n, lo + kDotBlock);
      double s = 0;
      for (long r = lo / nx; r <= (hi - 1) / nx; ++r)
        for (int q = act.begin(int(r)); q < act.end(int(r)); ++q) {
          const long a0 = std::max(lo, nx * r + act.lo(q)), a1 = std::min(hi, nx * r + act.hi(q));
          for (long c = a0; c < a1; ++c) s += a[c] * b[c];
        }
      part[blk] = s;
    }
  }
  double s = 0;
  for (double v : part) s += v;
  return s;
}

realtype op_dot(N_Vector a, N_Vector b) {
  const Cells& cs = cells_of(a);
  return cs.act ? segment_dot(cs, data(a), data(b), len(a)) : dot(data(a), data(b), len(a));
}
void op_linearsum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for_cells(cells_of(z), len(z), [&](long c0, long c1) {
    for (long i = c0; i < c1; ++i) zd[i] = a * xd[i] + b * yd[i];
  });
}
void op_scale(realtype a, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for_cells(cells_of(z), len(z), [&](long c0, long c1) {
    for (long i = c0; i < c1; ++i) zd[i] = a * xd[i];
  });
}
// Prod and Const are not repeated per iteration: every cell.
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

N_Vector make_vector(SUNContext ctx, N_Vector_Ops ops, long n, double* d, bool own, const Cells* cells);

N_Vector op_clone_empty(N_Vector w) {
  return make_vector(w->sunctx, w->ops, len(w), nullptr, false, &cells_of(w));
}
N_Vector op_clone(N_Vector w) {  // owns zeroed data (the cells outside the segments stay finite)
  return make_vector(w->sunctx, w->ops, len(w), new double[len(w)](), true, &cells_of(w));
}
void op_destroy(N_Vector v) {
  if (!v) return;
  auto* c = static_cast<Content*>(v->content);
  if (c) {
    if (c->serial.own_data) delete[] c->serial.data;
    delete c;
    v->content = nullptr;
  }
  N_VFreeEmpty(v);
}

// A vector of length n on d (owned or not), with the serial vector's operations and ours.
N_Vector make_vector(SUNContext ctx, N_Vector_Ops ops, long n, double* d, bool own, const Cells* cells) {
  N_Vector v = N_VNewEmpty(ctx);
  if (!v) throw Error("pressure: N_VNewEmpty failed");
  if (ops) {
    std::memcpy(v->ops, ops, sizeof(*ops));
  } else {
    N_Vector serial = N_VNewEmpty_Serial(n, ctx);  // the stock serial operations
    if (!serial) throw Error("pressure: N_VNewEmpty_Serial failed");
    N_VCopyOps(serial, v);
    N_VDestroy(serial);
    v->ops->nvclone = op_clone;
    v->ops->nvcloneempty = op_clone_empty;
    v->ops->nvdestroy = op_destroy;
    v->ops->nvdotprod = op_dot;
    v->ops->nvlinearsum = op_linearsum;
    v->ops->nvscale = op_scale;
    v->ops->nvprod = op_prod;
    v->ops->nvconst = op_const;
  }
  auto* c = new Content;
  c->serial.length = n;
  c->serial.own_data = own ? SUNTRUE : SUNFALSE;
  c->serial.data = d;
  c->cells = cells;
  v->content = c;
  return v;
}
}  // namespace

struct SundialsPcg::Impl {
  Cells cells;
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

SundialsPcg::SundialsPcg(long n, Apply op, Apply prec, const ActiveRows* active, int nx) : impl_(new Impl) {
  auto& m = *impl_;
  m.n = n;
  m.cells.act = active;
  m.cells.nx = nx;
  m.op = std::move(op);
  m.prec = std::move(prec);
  if (SUNContext_Create(nullptr, &m.ctx) != 0) throw Error("pressure: SUNContext_Create failed");
  m.xv = make_vector(m.ctx, nullptr, n, nullptr, false, &m.cells);
  m.bv = make_vector(m.ctx, m.xv->ops, n, nullptr, false, &m.cells);
  const int pretype = m.prec ? SUN_PREC_LEFT : SUN_PREC_NONE;
  // PCG clones its work vectors (with our operations and cells) from the template.
  m.ls = SUNLinSol_PCG(m.xv, pretype, 100, m.ctx);
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
