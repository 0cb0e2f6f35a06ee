// Single-precision 7-point operator for the multigrid V-cycle; see stencil32.hpp.
// No floating-point contraction: the AVX2 / AVX-512 clones below would otherwise fuse
// multiply-adds, and every build must compute the baseline's bits.
#pragma GCC optimize("fp-contract=off")
#include "solvers/pressure/stencil32.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "solvers/pressure/stencil_rows.hpp"

namespace cgdem::pressure {

double stencil32_scale(const Poisson7& op) {
  double m = 0;
  for (double v : op.diag()) m = std::max(m, v);
  if (!(m > 0)) return 1.0;
  return std::ldexp(1.0, -static_cast<int>(std::lround(std::log2(m))));
}

void Stencil32::set(const Poisson7& op, double scale, double omega, const ActiveRows* active) {
  const bool resized = g_.nx != op.grid().nx || g_.ny != op.grid().ny || g_.nz != op.grid().nz;
  g_ = op.grid();
  if (active) {
    if (active->rows() != g_.ny * g_.nz) throw Error("pressure: active cells of another grid");
    act_ = *active;
  } else if (resized || act_.rows() != g_.ny * g_.nz || act_.cells() != n()) {
    act_.all(g_.nx, g_.ny, g_.nz);
  }
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
// The update of the cells i = first, first + 2, ... < end of one row, all with both x
// neighbours in the row (1 <= first, end <= nx - 1), written without branches so that it
// vectorises (stride 2), in the summation order of Poisson7::gs_row; id = omega/D (0 where
// D = 0: that cell is set to keep x), keep = 1 - omega (0: the plain update, which does not
// read x_c).
// Compiled for AVX-512, AVX2 and the baseline; the arithmetic is the same IEEE float either way
// (contraction is off for the whole file, above).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void gs_interior(
    int first, int end, const float* __restrict br, const float* __restrict id, const float* __restrict wxr,
    const float* __restrict ws, const float* __restrict wn, const float* __restrict wb, const float* __restrict wt,
    const float* xs, const float* xn, const float* xb, const float* xt, float* xr, float keep) {
  if (keep != 0.0f) {
    for (int i = first; i < end; i += 2) {
      float s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
      s += wxr[i] * xr[i - 1];
      s += wxr[i + 1] * xr[i + 1];
      xr[i] = keep * xr[i] + s * id[i];
    }
    return;
  }
  for (int i = first; i < end; i += 2) {
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

// One colour of row (j, k), as Poisson7::gs_row in float, over the row's segments; the modes:
// stencil32.hpp.
void Stencil32::gs_row(const float* b, float* x, int j, int k, int color, Mode mode) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const int r = j + ny * k;
  if (act_.begin(r) == act_.end(r)) return;
  const long c0 = long(nx) * r;
  float* xr = x + c0;
  const float* br = b + c0;
  const float* id = id_.data() + c0;
  const int i0 = (j + k + color) & 1;
  auto first_of = [i0](int a) { return a + ((a ^ i0) & 1); };  // the first cell of the colour from a on
  if (mode == Mode::kZeroFirst) {
    for (int q = act_.begin(r); q < act_.end(r); ++q)
      for (int i = first_of(act_.lo(q)); i < act_.hi(q); i += 2) xr[i] = br[i] * id[i];
    return;
  }
  const float* wxr = wx_.data() + long(nx + 1) * r;
  const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
      row_neighbours<float>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py_, pz_);
  const float keep = mode == Mode::kFromZero ? 0.0f : keep_;
  auto edge = [&](int i) {  // i = 0 or nx - 1: the x neighbours may wrap or be absent
    float s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
    if (i > 0) s += wxr[i] * xr[i - 1]; else if (px_) s += wxr[0] * xr[nx - 1];
    if (i < nx - 1) s += wxr[i + 1] * xr[i + 1]; else if (px_) s += wxr[0] * xr[0];
    xr[i] = keep != 0.0f ? keep * xr[i] + s * id[i] : s * id[i];
  };
  for (int q = act_.begin(r); q < act_.end(r); ++q) {
    const int lo = act_.lo(q), hi = act_.hi(q);
    if (lo == 0 && i0 == 0) edge(0);
    const int a = std::max(lo, 1), e = std::min(hi, nx - 1);
    if (a < e) gs_interior(first_of(a), e, br, id, wxr, ws, wn, wb, wt, xs, xn, xb, xt, xr, keep);
    if (hi == nx && (nx - 1 - i0) % 2 == 0 && nx - 1 > 0) edge(nx - 1);
  }
}

// Rows shared by active cells between the threads (active_rows.hpp); each row depends only
// on cells of the other colour, so the split does not change the result.
void Stencil32::gs_color(const float* b, float* x, int color, Mode mode) const {
  const int ny = g_.ny, nz = g_.nz;
  const long plane = long(g_.nx) * ny;
  const bool odd_wrap = (py_ && ny % 2) || (pz_ && nz % 2);
#pragma omp parallel if (!odd_wrap && plane * nz >= kParallelMin)
  {
    int r0, r1;
    act_.share(omp_get_thread_num(), omp_get_num_threads(), r0, r1);
    for (int r = r0; r < r1; ++r) gs_row(b, x, r % ny, r / ny, color, mode);
  }
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
  // Each thread's planes, balanced by active cells: any split of the planes gives the same
  // result (Poisson7::gauss_seidel_pair).
#pragma omp parallel if (plane * nz >= kParallelMin)
  {
    int ka, kb;
    act_.share_planes(omp_get_thread_num(), omp_get_num_threads(), ka, kb);
    for (int k = ka; k < kb; ++k) {
      plane_sweep(k, first, m1);
      if (k - 1 > ka && k - 1 < kb - 1) plane_sweep(k - 1, second, m2);
    }
#pragma omp barrier
    if (kb > ka) plane_sweep(ka, second, m2);
    if (kb - 1 > ka) plane_sweep(kb - 1, second, m2);
  }
}

// r = b - A x on the cells [lo, hi) of row (j, k) (the arithmetic of Poisson7::apply_rows, in
// float; r indexed by i).
void Stencil32::residual_row(const float* b, const float* x, int j, int k, int lo, int hi, float* r) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const long c0 = long(nx) * (j + long(ny) * k);
  const float* xr = x + c0;
  const float* br = b + c0;
  const float* d = d_.data() + c0;
  const float* wxr = wx_.data() + long(nx + 1) * (j + long(ny) * k);
  const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
      row_neighbours<float>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py_, pz_);
  residual_interior(hi - lo, br + lo, d + lo, xr + lo, wxr + lo, ws + lo, wn + lo, wb + lo, wt + lo, xs + lo, xn + lo,
                    xb + lo, xt + lo, r + lo);
  if (px_) {  // the segments of a periodic x axis are whole rows
    r[0] += wxr[0] * xr[nx - 1];
    r[nx - 1] += wxr[0] * xr[0];
  }
}

void Stencil32::restrict_residual(const float* b, const float* x, const GridSpec& c, float* bc) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  if (c.nx != (nx + 1) / 2 || c.ny != (ny + 1) / 2 || c.nz != (nz + 1) / 2)
    throw Error("pressure: restriction onto a grid that is not this one coarsened by 2");
#pragma omp parallel if (n() >= kParallelMin)
  {
    std::vector<float> row(nx);
    int R0, R1;
    act_.share_coarse(omp_get_thread_num(), omp_get_num_threads(), R0, R1);
    for (int R = R0; R < R1; ++R) {
      const int J = R % c.ny, K = R / c.ny;
      float* out = bc + long(c.nx) * R;
      std::fill(out, out + c.nx, 0.0f);
      for (int k = 2 * K; k <= std::min(2 * K + 1, nz - 1); ++k)
        for (int j = 2 * J; j <= std::min(2 * J + 1, ny - 1); ++j) {
          const int r = j + ny * k;
          for (int q = act_.begin(r); q < act_.end(r); ++q) {
            const int lo = act_.lo(q), hi = act_.hi(q);
            residual_row(b, x, j, k, lo, hi, row.data());
            for (int i = lo; i < hi; ++i) out[i / 2] += row[i];
          }
        }
      for (int I = 0; I < c.nx; ++I) out[I] *= 0.125f;
    }
  }
}

void Stencil32::prolong_add(const GridSpec& c, const float* xc, float* x) const {
  const int nx = g_.nx, ny = g_.ny;
#pragma omp parallel if (n() >= kParallelMin)
  {
    int r0, r1;
    act_.share(omp_get_thread_num(), omp_get_num_threads(), r0, r1);
    for (int r = r0; r < r1; ++r) {
      const int j = r % ny, k = r / ny;
      const float* xcr = xc + long(c.nx) * (j / 2 + long(c.ny) * (k / 2));
      float* xf = x + long(nx) * r;
      for (int q = act_.begin(r); q < act_.end(r); ++q)
        for (int i = act_.lo(q); i < act_.hi(q); ++i) xf[i] += xcr[i / 2];
    }
  }
}

}  // namespace cgdem::pressure
