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
}  // namespace

FusedPcg::Result FusedPcg::solve(const double* b, double* x, double abs_tol, int max_iter, bool zero_guess) {
  const long n = op_.n(), nb = blocks(n);
  r_.resize(n), z_.resize(n), p_.resize(n), q_.resize(n), part_.resize(nb);
  double *r = r_.data(), *z = z_.data(), *p = p_.data(), *q = q_.data(), *part = part_.data();
  const bool par = n >= kParallelMin;
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
  if (prec_) prec_(r, z);
  else std::copy(r, r + n, z);
  // rz = r.z and p = z in one pass
#pragma omp parallel for schedule(static) if (par)
  for (long blk = 0; blk < nb; ++blk) {
    double s = 0;
    for (long c = blk * kBlock; c < std::min(n, (blk + 1) * kBlock); ++c) s += r[c] * z[c], p[c] = z[c];
    part[blk] = s;
  }
  double rz = sum(part_);
  for (int it = 1; it <= max_iter; ++it) {
    const double pq = op_.apply_dot(p, q);
    if (!(pq > 0) || !std::isfinite(pq)) return res;  // breakdown: not converged
    const double alpha = rz / pq;
    // x += alpha p, r -= alpha q, r.r
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
    rho = std::sqrt(sum(part_));
    res.iterations = it;
    res.res_norm = rho;
    if (rho <= abs_tol) {
      res.converged = true;
      return res;
    }
    if (prec_) prec_(r, z);
    else std::copy(r, r + n, z);
    const double rz_new = dot(r, z, n);
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (par)
    for (long c = 0; c < n; ++c) p[c] = z[c] + beta * p[c];
  }
  return res;
}

}  // namespace cgdem::pressure
