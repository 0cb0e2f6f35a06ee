// PCG with fused vector passes; see fused_pcg.hpp.
#include "solvers/pressure/fused_pcg.hpp"

#include <algorithm>
#include <cmath>

namespace cgdem::pressure {

namespace {
constexpr long kBlock = 4096;  // the blocking of dot() in poisson7.cpp
long blocks(long n) { return (n + kBlock - 1) / kBlock; }
double sum(const std::vector<double>& part) {
  double s = 0;
  for (double v : part) s += v;
  return s;
}

// The fused passes, blocked as dot() in poisson7.cpp (each block's partial sum in `part`,
// added in block order: the sums do not depend on the number of threads).

// rz = r.z and p = z in one pass.
double dot_and_copy(const double* r, const double* z, double* p, std::vector<double>& part, long n, bool par) {
  const long nb = blocks(n);
#pragma omp parallel for schedule(static) if (par)
  for (long blk = 0; blk < nb; ++blk) {
    double s = 0;
    for (long c = blk * kBlock; c < std::min(n, (blk + 1) * kBlock); ++c) s += r[c] * z[c], p[c] = z[c];
    part[blk] = s;
  }
  return sum(part);
}

// x += alpha p, r -= alpha q, and |r| in one pass.
double update_and_norm(double alpha, const double* p, const double* q, double* x, double* r, std::vector<double>& part,
                       long n, bool par) {
  const long nb = blocks(n);
#pragma omp parallel for schedule(static) if (par)
  for (long blk = 0; blk < nb; ++blk) {
    double s = 0;
    for (long c = blk * kBlock; c < std::min(n, (blk + 1) * kBlock); ++c) {
      x[c] += alpha * p[c];
      r[c] -= alpha * q[c];
      s += r[c] * r[c];
    }
    part[blk] = s;
  }
  return std::sqrt(sum(part));
}

}  // namespace

// Preconditioned CG from x (or from 0): stops when |r| <= abs_tol (converged) or after
// max_iter iterations, or on a breakdown (p.Ap not positive and finite: not converged).
FusedPcg::Result FusedPcg::solve(const double* b, double* x, double abs_tol, int max_iter, bool zero_guess) {
  const long n = op_.n(), nb = blocks(n);
  r_.resize(n), z_.resize(n), p_.resize(n), q_.resize(n), part_.resize(nb);
  double *r = r_.data(), *z = z_.data(), *p = p_.data(), *q = q_.data();
  const bool par = n >= kParallelMin;
  // z = M^-1 r (M = 1 without a preconditioner).
  auto precondition = [&] {
    if (prec_) prec_(r, z);
    else std::copy(r, r + n, z);
  };
  Result res;
  if (zero_guess) {
#pragma omp parallel for schedule(static) if (par)
    for (long c = 0; c < n; ++c) x[c] = 0.0, r[c] = b[c];
  } else {
    op_.residual(b, x, r);
  }
  double rho = norm2(r, n);
  res.res_norm = rho;
  if (rho <= abs_tol) {
    res.converged = true;
    return res;
  }
  precondition();
  double rz = dot_and_copy(r, z, p, part_, n, par);
  for (int it = 1; it <= max_iter; ++it) {
    const double pq = op_.apply_dot(p, q);
    if (!(pq > 0) || !std::isfinite(pq)) return res;  // breakdown: not converged
    const double alpha = rz / pq;
    rho = update_and_norm(alpha, p, q, x, r, part_, n, par);
    res.iterations = it;
    res.res_norm = rho;
    if (rho <= abs_tol) {
      res.converged = true;
      return res;
    }
    precondition();
    const double rz_new = dot(r, z, n);
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (par)
    for (long c = 0; c < n; ++c) p[c] = z[c] + beta * p[c];
  }
  return res;
}

}  // namespace cgdem::pressure
