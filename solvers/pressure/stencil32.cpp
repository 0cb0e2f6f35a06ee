// Single-precision 7-point operator for the multigrid V-cycle; see stencil32.hpp.
// No floating-point contraction: the AVX2 / AVX-512 clones below would otherwise fuse
// multiply-adds, and every build must compute the baseline's bits.
#pragma GCC optimize("fp-contract=off")
#include "solvers/pressure/stencil32.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "solvers/pressure/stencil_rows.hpp"

namespace cgdem::pressure {

double stencil32_scale(const Poisson7& op) {
  double m = 0;
  for (double v : op.diag()) m = std::max(m, v);
  if (!(m > 0)) return 1.0;
  return std::ldexp(1.0, -static_cast<int>(std::lround(std::log2(m))));
}

void Stencil32::set(const Poisson7& op, double scale, double omega) {
  g_ = op.grid();
  px_ = op.periodic(0), py_ = op.periodic(1), pz_ = op.periodic(2);
  auto copy = [scale](const std::vector<double>& in, std::vector<float>& out) {
    out.resize(in.size());
    const long n = static_cast<long>(in.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (long q = 0; q < n; ++q) out[q] = static_cast<float>(scale * in[q]);
  };
  copy(op.wx(), wx_);
  copy(op.wy(), wy_);
  copy(op.wz(), wz_);
  copy(op.diag(), d_);
  id_.resize(d_.size());
  const float om = static_cast<float>(omega);
  keep_ = 1.0f - om;
  const long n = static_cast<long>(d_.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long c = 0; c < n; ++c) id_[c] = d_[c] > 0 ? om / d_[c] : 0.0f;
}

namespace {
// The update of the cells i = i0, i0 + 2, ... < nx of one row that have both x neighbours in the
// row (1 <= i <= nx - 2), written without branches so that it vectorises (stride 2), in the
// summation order of Poisson7::gs_row; id = omega/D (0 where D = 0: that cell is set to keep x),
// keep = 1 - omega (0: the plain update, which does not read x_c).
// Compiled for AVX-512, AVX2 and the baseline; the arithmetic is the same IEEE float either way
// (contraction is off for the whole file, above).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void gs_interior(
    int i0, int nx, const float* __restrict br, const float* __restrict id, const float* __restrict wxr,
    const float* __restrict ws, const float* __restrict wn, const float* __restrict wb, const float* __restrict wt,
    const float* xs, const float* xn, const float* xb, const float* xt, float* xr, float keep) {
  const int first = i0 == 0 ? 2 : i0;
  if (keep != 0.0f) {
    for (int i = first; i < nx - 1; i += 2) {
      float s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
      s += wxr[i] * xr[i - 1];
      s += wxr[i + 1] * xr[i + 1];
      xr[i] = keep * xr[i] + s * id[i];
    }
    return;
  }
  for (int i = first; i < nx - 1; i += 2) {
    float s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
    s += wxr[i] * xr[i - 1];
    s += wxr[i + 1] * xr[i + 1];
    xr[i] = s * id[i];
  }
}

// r = b - A x along one row without its periodic wrap (residual_row adds that): the
// arithmetic of Poisson7::apply_rows in float, built like gs_interior.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void residual_interior(
    int nx, const float* __restrict br, const float* __restrict d, const float* __restrict xr,
    const float* __restrict wxr, const float* __restrict ws, const float* __restrict wn, const float* __restrict wb,
    const float* __restrict wt, const float* xs, const float* xn, const float* xb, const float* xt,
    float* __restrict r) {
  for (int i = 0; i < nx; ++i)
    r[i] = br[i] - d[i] * xr[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
  for (int i = 1; i < nx; ++i) r[i] += wxr[i] * xr[i - 1];
  for (int i = 0; i < nx - 1; ++i) r[i] += wxr[i + 1] * xr[i + 1];
}
}  // namespace

// One colour of row (j, k), as Poisson7::gs_row in float; the modes: stencil32.hpp.
void Stencil32::gs_row(const float* b, float* x, int j, int k, int color, Mode mode) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const long c0 = long(nx) * (j + long(ny) * k);
  float* xr = x + c0;
  const float* br = b + c0;
  const float* id = id_.data() + c0;
  const int i0 = (j + k + color) & 1;
  if (mode == Mode::kZeroFirst) {
    for (int i = i0; i < nx; i += 2) xr[i] = br[i] * id[i];
    return;
  }
  const float* wxr = wx_.data() + long(nx + 1) * (j + long(ny) * k);
  const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
      row_neighbours<float>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py_, pz_);
  const float keep = mode == Mode::kFromZero ? 0.0f : keep_;
  auto edge = [&](int i) {  // i = 0 or nx - 1: the x neighbours may wrap or be absent
    float s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
    if (i > 0) s += wxr[i] * xr[i - 1]; else if (px_) s += wxr[0] * xr[nx - 1];
    if (i < nx - 1) s += wxr[i + 1] * xr[i + 1]; else if (px_) s += wxr[0] * xr[0];
    xr[i] = keep != 0.0f ? keep * xr[i] + s * id[i] : s * id[i];
  };
  if (i0 == 0) edge(0);
  gs_interior(i0, nx, br, id, wxr, ws, wn, wb, wt, xs, xn, xb, xt, xr, keep);
  if ((nx - 1 - i0) % 2 == 0 && nx - 1 > 0) edge(nx - 1);
}

void Stencil32::gs_color(const float* b, float* x, int color, Mode mode) const {
  const int ny = g_.ny, nz = g_.nz;
  const long plane = long(g_.nx) * ny;
  const bool odd_wrap = (py_ && ny % 2) || (pz_ && nz % 2);
#pragma omp parallel for collapse(2) schedule(static) if (!odd_wrap && plane * nz >= kParallelMin)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) gs_row(b, x, j, k, color, mode);
}

void Stencil32::gs_pair(const float* b, float* x, int first, bool zero_start) const {
  const int ny = g_.ny, nz = g_.nz;
  const long plane = long(g_.nx) * ny;
  const bool odd_wrap = (py_ && ny % 2) || (pz_ && nz % 2) || (px_ && g_.nx % 2);
  if (zero_start && odd_wrap) {  // same-colour neighbours at the wrap: start from a real zero
    std::fill(x, x + n(), 0.0f);
    zero_start = false;
  }
  const Mode m1 = zero_start ? Mode::kZeroFirst : Mode::kNormal, m2 = zero_start ? Mode::kFromZero : Mode::kNormal;
  const int second = 1 - first;
  if (odd_wrap || pz_ || nz < 4) {  // plane 0 and nz-1 are neighbours: two plain sweeps
    gs_color(b, x, first, m1);
    gs_color(b, x, second, m2);
    return;
  }
  auto plane_sweep = [&](int k, int color, Mode m) {
    for (int j = 0; j < ny; ++j) gs_row(b, x, j, k, color, m);
  };
#pragma omp parallel if (plane * nz >= kParallelMin)
  {
    const int nth = omp_get_num_threads(), tid = omp_get_thread_num();
    const int ka = int(long(nz) * tid / nth), kb = int(long(nz) * (tid + 1) / nth);
    for (int k = ka; k < kb; ++k) {
      plane_sweep(k, first, m1);
      if (k - 1 > ka && k - 1 < kb - 1) plane_sweep(k - 1, second, m2);
    }
#pragma omp barrier
    if (kb > ka) plane_sweep(ka, second, m2);
    if (kb - 1 > ka) plane_sweep(kb - 1, second, m2);
  }
}

// r = b - A x on row (j, k) (the arithmetic of Poisson7::apply_rows, in float).
void Stencil32::residual_row(const float* b, const float* x, int j, int k, float* r) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const long c0 = long(nx) * (j + long(ny) * k);
  const float* xr = x + c0;
  const float* br = b + c0;
  const float* d = d_.data() + c0;
  const float* wxr = wx_.data() + long(nx + 1) * (j + long(ny) * k);
  const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
      row_neighbours<float>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py_, pz_);
  residual_interior(nx, br, d, xr, wxr, ws, wn, wb, wt, xs, xn, xb, xt, r);
  if (px_) {
    r[0] += wxr[0] * xr[nx - 1];
    r[nx - 1] += wxr[0] * xr[0];
  }
}

void Stencil32::restrict_residual(const float* b, const float* x, const GridSpec& c, float* bc) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
#pragma omp parallel if (n() >= kParallelMin)
  {
    std::vector<float> row(nx);
#pragma omp for collapse(2) schedule(static)
    for (int K = 0; K < c.nz; ++K)
      for (int J = 0; J < c.ny; ++J) {
        float* out = bc + long(c.nx) * (J + long(c.ny) * K);
        std::fill(out, out + c.nx, 0.0f);
        for (int k = 2 * K; k <= std::min(2 * K + 1, nz - 1); ++k)
          for (int j = 2 * J; j <= std::min(2 * J + 1, ny - 1); ++j) {
            residual_row(b, x, j, k, row.data());
            for (int i = 0; i < nx; ++i) out[i / 2] += row[i];
          }
        for (int I = 0; I < c.nx; ++I) out[I] *= 0.125f;
      }
  }
}

void Stencil32::prolong_add(const GridSpec& c, const float* xc, float* x) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
#pragma omp parallel for collapse(2) schedule(static) if (n() >= kParallelMin)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const float* xcr = xc + long(c.nx) * (j / 2 + long(c.ny) * (k / 2));
      float* xf = x + long(nx) * (j + long(ny) * k);
      for (int i = 0; i < nx; ++i) xf[i] += xcr[i / 2];
    }
}

}  // namespace cgdem::pressure
