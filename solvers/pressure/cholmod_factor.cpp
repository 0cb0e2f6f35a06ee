// CHOLMOD factorisation of the pinned 7-point operator; see cholmod_factor.hpp.
#include "solvers/pressure/cholmod_factor.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace cgdem::pressure {

struct CholmodFactor::Impl {
  cholmod_common c;
  cholmod_factor* L = nullptr;
  cholmod_dense* B = nullptr;
  long n = 0;
  std::vector<SuiteSparse_long> p, i;  // the pattern L was analysed for (column starts, rows)
  Impl() { cholmod_l_start(&c); }
  ~Impl() {
    if (B) cholmod_l_free_dense(&B, &c);
    if (L) cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
  }
};

namespace {
// Neighbours (index, weight) of cell (i,j,k) through its 6 faces, periodic wraps included.
template <class F>
void for_each_link(const Poisson7& op, int i, int j, int k, F&& f) {
  const auto& g = op.grid();
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  auto cell = [&](int a, int b, int d) { return a + long(nx) * (b + long(ny) * d); };
  auto fx = [&](int a) { return op.wx()[a + long(nx + 1) * (j + long(ny) * k)]; };
  auto fy = [&](int b) { return op.wy()[i + long(nx) * (b + long(ny + 1) * k)]; };
  auto fz = [&](int d) { return op.wz()[i + long(nx) * (j + long(ny) * d)]; };
  const bool px = op.periodic(0), py = op.periodic(1), pz = op.periodic(2);
  if (i > 0) f(cell(i - 1, j, k), fx(i)); else if (px) f(cell(nx - 1, j, k), fx(0));
  if (i < nx - 1) f(cell(i + 1, j, k), fx(i + 1)); else if (px) f(cell(0, j, k), fx(0));
  if (j > 0) f(cell(i, j - 1, k), fy(j)); else if (py) f(cell(i, ny - 1, k), fy(0));
  if (j < ny - 1) f(cell(i, j + 1, k), fy(j + 1)); else if (py) f(cell(i, 0, k), fy(0));
  if (k > 0) f(cell(i, j, k - 1), fz(k)); else if (pz) f(cell(i, j, nz - 1), fz(0));
  if (k < nz - 1) f(cell(i, j, k + 1), fz(k + 1)); else if (pz) f(cell(i, j, 0), fz(0));
}
}  // namespace

namespace {
// The pinned matrix A' of op (lower triangle, stype -1; see the header), allocated in m.c.
cholmod_sparse* assemble(const Poisson7& op, cholmod_common& cc) {
  const auto& g = op.grid();
  const long n = op.n();
  // Pin the first cell of every floating component.
  std::vector<double> pin(n, 0.0);
  std::vector<char> seen(op.floating_components(), 0);
  for (long c = 0; c < n; ++c) {
    const int q = op.floating_id()[c];
    if (q >= 0 && !seen[q]) {
      seen[q] = 1;
      pin[c] = op.diag()[c] > 0 ? op.diag()[c] : 1.0;
    }
  }
  cholmod_sparse* A = cholmod_l_allocate_sparse(n, n, 4 * n, 1, 1, -1, CHOLMOD_REAL, &cc);
  if (!A) throw Error("pressure: CHOLMOD could not allocate the matrix");
  auto* Ap = static_cast<SuiteSparse_long*>(A->p);
  auto* Ai = static_cast<SuiteSparse_long*>(A->i);
  auto* Ax = static_cast<double*>(A->x);
  long nnz = 0;
  std::vector<std::pair<long, double>> col;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const long c = i + long(g.nx) * (j + long(g.ny) * k);
        double d = op.diag()[c] + pin[c];
        col.clear();
        for_each_link(op, i, j, k, [&](long nb, double w) {
          if (w == 0) return;
          if (nb == c) d -= w;  // a one-cell periodic axis links a cell to itself
          else if (nb > c) col.emplace_back(nb, -w);
        });
        std::sort(col.begin(), col.end());
        Ap[c] = nnz;
        Ai[nnz] = c;
        Ax[nnz++] = d;
        for (size_t q = 0; q < col.size(); ++q) {
          if (q > 0 && col[q].first == col[q - 1].first) { Ax[nnz - 1] += col[q].second; continue; }
          Ai[nnz] = col[q].first;
          Ax[nnz++] = col[q].second;
        }
      }
  Ap[n] = nnz;
  return A;
}
}  // namespace

CholmodFactor::CholmodFactor(const Poisson7& op) : impl_(std::make_unique<Impl>()) { refactor(op); }

bool CholmodFactor::refactor(const Poisson7& op) {
  auto& m = *impl_;
  const long n = op.n();
  cholmod_sparse* A = assemble(op, m.c);
  const auto* Ap = static_cast<const SuiteSparse_long*>(A->p);
  const auto* Ai = static_cast<const SuiteSparse_long*>(A->i);
  const bool same = m.L && m.n == n && std::equal(m.p.begin(), m.p.end(), Ap, Ap + n + 1) &&
                    std::equal(m.i.begin(), m.i.end(), Ai, Ai + Ap[n]);
  if (!same) {
    if (m.L) cholmod_l_free_factor(&m.L, &m.c);
    if (m.B) cholmod_l_free_dense(&m.B, &m.c);
    m.n = n;
    m.p.assign(Ap, Ap + n + 1);
    m.i.assign(Ai, Ai + Ap[n]);
    m.L = cholmod_l_analyze(A, &m.c);
  }
  const bool ok = m.L && cholmod_l_factorize(A, m.L, &m.c) && m.c.status == CHOLMOD_OK;
  cholmod_l_free_sparse(&A, &m.c);
  if (!ok) {
    if (m.L) cholmod_l_free_factor(&m.L, &m.c);  // analysed anew next time
    throw Error("pressure: CHOLMOD factorisation failed (status " + std::to_string(m.c.status) + ")");
  }
  if (!m.B) m.B = cholmod_l_allocate_dense(n, 1, n, CHOLMOD_REAL, &m.c);
  return same;
}

CholmodFactor::~CholmodFactor() = default;

void CholmodFactor::solve(const double* b, double* x) {
  auto& m = *impl_;
  std::memcpy(m.B->x, b, sizeof(double) * m.n);
  cholmod_dense* X = cholmod_l_solve(CHOLMOD_A, m.L, m.B, &m.c);
  if (!X) throw Error("pressure: CHOLMOD solve failed");
  std::memcpy(x, X->x, sizeof(double) * m.n);
  cholmod_l_free_dense(&X, &m.c);
}

double CholmodFactor::factor_nonzeros() const {
  const auto* L = impl_->L;
  return L->is_super ? double(L->xsize) : double(static_cast<SuiteSparse_long*>(L->p)[L->n]);
}

}  // namespace cgdem::pressure
