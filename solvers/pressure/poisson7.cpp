// 7-point operator A = -div(a grad .) on the cell-centred grid; see poisson7.hpp.
// No floating-point contraction: the AVX2 / AVX-512 builds of apply_interior would
// otherwise fuse multiply-adds, and every build must compute the baseline's bits.
#pragma GCC optimize("fp-contract=off")
#include "solvers/pressure/poisson7.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "solvers/pressure/stencil_rows.hpp"
#include "solvers/pressure/union_find.hpp"

namespace cgdem::pressure {

namespace {
constexpr long kBlock = 4096;  // fixed reduction blocks: sums independent of the thread count

void check_size(const std::vector<double>& a, long want, const char* name) {
  if (static_cast<long>(a.size()) != want)
    throw Error(std::string("pressure: face coefficient array ") + name + " has " +
                std::to_string(a.size()) + " entries, expected " + std::to_string(want));
  // Counted without an early exit, so that the loop vectorises (NaN fails both comparisons).
  long bad = 0;
  const double* v = a.data();
  const double top = std::numeric_limits<double>::max();
#pragma omp parallel for schedule(static) reduction(+ : bad) if (want >= kParallelMin)
  for (long q = 0; q < want; ++q) bad += !(v[q] >= 0.0 && v[q] <= top);
  if (bad) throw Error(std::string("pressure: face coefficient ") + name + " must be finite and >= 0");
}

// True when a and b have the same size and the same faces (or cells) with a value > 0
// (counted without an early exit, so that the loop vectorises).
bool same_sign_pattern(const std::vector<double>& a, const std::vector<double>& b, bool par) {
  if (a.size() != b.size()) return false;
  const long m = static_cast<long>(a.size());
  const double *x = a.data(), *y = b.data();
  long differ = 0;
#pragma omp parallel for schedule(static) reduction(+ : differ) if (par)
  for (long q = 0; q < m; ++q) differ += (x[q] > 0) != (y[q] > 0);
  return differ == 0;
}

// y = A x along one row without its periodic wrap (apply_rows adds that). Built for AVX-512,
// AVX2 and the baseline; contraction is off for the file, so every build gives the same bits.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void apply_interior(
    int nx, const double* __restrict d, const double* __restrict xr, const double* __restrict wxr,
    const double* __restrict ws, const double* __restrict wn, const double* __restrict wb,
    const double* __restrict wt, const double* xs, const double* xn, const double* xb, const double* xt,
    double* __restrict yr) {
  for (int i = 0; i < nx; ++i)
    yr[i] = d[i] * xr[i] - ws[i] * xs[i] - wn[i] * xn[i] - wb[i] * xb[i] - wt[i] * xt[i];
  for (int i = 1; i < nx; ++i) yr[i] -= wxr[i] * xr[i - 1];
  for (int i = 0; i < nx - 1; ++i) yr[i] -= wxr[i + 1] * xr[i + 1];
}
}  // namespace

double dot(const double* a, const double* b, long n) {
  const long nb = (n + kBlock - 1) / kBlock;
  std::vector<double> part(nb);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long blk = 0; blk < nb; ++blk) {
    const long lo = blk * kBlock, hi = std::min(n, lo + kBlock);
    double s = 0;
    for (long i = lo; i < hi; ++i) s += a[i] * b[i];
    part[blk] = s;
  }
  double s = 0;
  for (double p : part) s += p;
  return s;
}

Poisson7::Poisson7(const GridSpec& g) : g_(g) {
  if (g.nx < 1 || g.ny < 1 || g.nz < 1)
    throw Error("pressure: grid needs nx, ny, nz >= 1 (got " + std::to_string(g.nx) + "x" +
                std::to_string(g.ny) + "x" + std::to_string(g.nz) + ")");
  if (!(g.dx > 0) || !(g.dy > 0) || !(g.dz > 0)) throw Error("pressure: grid spacings must be > 0");
  for (int ax = 0; ax < 3; ++ax) {
    const bool lo = g.bc[2 * ax] == Boundary::Periodic, hi = g.bc[2 * ax + 1] == Boundary::Periodic;
    if (lo != hi) throw Error("pressure: a Periodic boundary needs both sides of its axis Periodic");
  }
}

void Poisson7::set(const std::vector<double>& ax, const std::vector<double>& ay,
                   const std::vector<double>& az) {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  check_size(ax, long(nx + 1) * ny * nz, "ax");
  check_size(ay, long(nx) * (ny + 1) * nz, "ay");
  check_size(az, long(nx) * ny * (nz + 1), "az");
  const bool par = n() >= kParallelMin;
  // Copied, and below every weight, diag and open entry written, on the threads and without a
  // serial fill first (the arrays keep their size from call to call).
  for (auto [src, dst] : {std::pair{&ax, &ax_}, std::pair{&ay, &ay_}, std::pair{&az, &az_}}) {
    dst->resize(src->size());
    const long m = static_cast<long>(src->size());
    const double* s = src->data();
    double* d = dst->data();
#pragma omp parallel for schedule(static) if (par)
    for (long q = 0; q < m; ++q) d[q] = s[q];
  }
  // The previous weights decide whether the connectivity (which faces have w > 0) changed.
  const bool had = !comp_.empty();
  if (had) old_w_[0].swap(wx_), old_w_[1].swap(wy_), old_w_[2].swap(wz_), old_w_[3].swap(open_);
  wx_.resize(ax.size());
  wy_.resize(ay.size());
  wz_.resize(az.size());
  diag_.resize(n());
  open_.resize(n());
  // Every cell sums its faces in the same order as a serial sweep x, y, z (face index
  // ascending): x and y faces touch one k plane (parallel over k), z faces one (i, j) column
  // (parallel over j), so the sums are those of the serial loops.
  add_xy_faces(ax, ay);
  add_z_faces(az);
  const long N = n();
#pragma omp parallel for schedule(static) if (par)
  for (long c = 0; c < N; ++c) diag_[c] += open_[c];
  // Same pattern of positive weights: the components (and floating cells) are unchanged.
  if (had && same_sign_pattern(old_w_[0], wx_, par) && same_sign_pattern(old_w_[1], wy_, par) &&
      same_sign_pattern(old_w_[2], wz_, par) && same_sign_pattern(old_w_[3], open_, par))
    return;
  label_components();
  active_.from_diag(diag_.data(), g_.nx, g_.ny, g_.nz, periodic(0));
  isolated_active_.clear();
  for (long c : isolated_cells_) {
    const int r = static_cast<int>(c / g_.nx), i = static_cast<int>(c % g_.nx);
    for (int q = active_.begin(r); q < active_.end(r); ++q)
      if (i >= active_.lo(q) && i < active_.hi(q)) isolated_active_.push_back(c);
  }
}

// x faces: interior, periodic wrap (face 0) or boundary (Open sides into open_); y faces
// likewise; one k plane per iteration of the parallel loop.
void Poisson7::add_xy_faces(const std::vector<double>& ax, const std::vector<double>& ay) {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const double hx = 1 / (g_.dx * g_.dx), hy = 1 / (g_.dy * g_.dy);
  const bool px = periodic(0), py = periodic(1);
  const auto& bc = g_.bc;
  const bool par = n() >= kParallelMin;
#pragma omp parallel for schedule(static) if (par)
  for (int k = 0; k < nz; ++k) {
    // diag and open of plane k start at 0 here: only this plane's faces touch them so far
    const long plane = long(nx) * ny;
    std::fill(diag_.begin() + plane * k, diag_.begin() + plane * (k + 1), 0.0);
    std::fill(open_.begin() + plane * k, open_.begin() + plane * (k + 1), 0.0);
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i <= nx; ++i) {  // x faces: interior, wrap (face 0) or boundary
        const long f = i + long(nx + 1) * (j + long(ny) * k);
        const long cl = (i - 1) + long(nx) * (j + long(ny) * k), cr = cl + 1;
        const double w = ax[f] * hx;
        double wf = 0.0;  // the weight coupling two cells (0: none)
        if (i > 0 && i < nx) { wf = w; diag_[cl] += w; diag_[cr] += w; }
        else if (px) { if (i == 0) { wf = w; diag_[cr] += w; diag_[cr + nx - 1] += w; } }
        else if (i == 0 && bc[0] == Boundary::Open) open_[cr] += 2 * w;
        else if (i == nx && bc[1] == Boundary::Open) open_[cl] += 2 * w;
        wx_[f] = wf;
      }
    }
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long f = i + long(nx) * (j + long(ny + 1) * k);
        const long cs = i + long(nx) * ((j - 1) + long(ny) * k), cn = cs + nx;
        const double w = ay[f] * hy;
        double wf = 0.0;
        if (j > 0 && j < ny) { wf = w; diag_[cs] += w; diag_[cn] += w; }
        else if (py) { if (j == 0) { wf = w; diag_[cn] += w; diag_[cn + long(nx) * (ny - 1)] += w; } }
        else if (j == 0 && bc[2] == Boundary::Open) open_[cn] += 2 * w;
        else if (j == ny && bc[3] == Boundary::Open) open_[cs] += 2 * w;
        wy_[f] = wf;
      }
  }
}

// z faces, likewise; one (i, j) column per iteration of the parallel loop (over j).
void Poisson7::add_z_faces(const std::vector<double>& az) {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const double hz = 1 / (g_.dz * g_.dz);
  const bool pz = periodic(2);
  const auto& bc = g_.bc;
  const bool par = n() >= kParallelMin;
  const long plane = long(nx) * ny;
#pragma omp parallel for schedule(static) if (par)
  for (int j = 0; j < ny; ++j)
    for (int k = 0; k <= nz; ++k)
      for (int i = 0; i < nx; ++i) {
        const long f = i + long(nx) * (j + long(ny) * k);
        const long cb = f - plane, ct = f;
        const double w = az[f] * hz;
        double wf = 0.0;
        if (k > 0 && k < nz) { wf = w; diag_[cb] += w; diag_[ct] += w; }
        else if (pz) { if (k == 0) { wf = w; diag_[ct] += w; diag_[ct + plane * (nz - 1)] += w; } }
        else if (k == 0 && bc[4] == Boundary::Open) open_[ct] += 2 * w;
        else if (k == nz && bc[5] == Boundary::Open) open_[cb] += 2 * w;
        wz_[f] = wf;
      }
}

void Poisson7::label_components() {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const long N = n();
  std::vector<int> parent(N);
  std::iota(parent.begin(), parent.end(), 0);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long c = i + long(nx) * (j + long(ny) * k);
        const long fx = i + long(nx + 1) * (j + long(ny) * k);
        const long fy = i + long(nx) * (j + long(ny + 1) * k);
        if (wx_[fx] > 0) unite(parent, c, i > 0 ? c - 1 : c + nx - 1);
        if (wy_[fy] > 0) unite(parent, c, j > 0 ? c - nx : c + long(nx) * (ny - 1));
        if (wz_[c] > 0) unite(parent, c, k > 0 ? c - long(nx) * ny : c + long(nx) * ny * (nz - 1));
      }
  std::vector<char> grounded(N, 0);
  for (long c = 0; c < N; ++c)
    if (open_[c] > 0) grounded[find_root(parent, c)] = 1;
  std::vector<int> id_of_root(N, -1);
  comp_.assign(N, -1);
  comp_count_.clear();
  floating_cells_.clear();
  n_floating_ = 0;
  for (long c = 0; c < N; ++c) {
    const int r = find_root(parent, c);
    if (grounded[r]) continue;
    if (id_of_root[r] < 0) {
      id_of_root[r] = n_floating_++;
      comp_count_.push_back(0.0);
    }
    comp_[c] = id_of_root[r];
    comp_count_[comp_[c]] += 1.0;
    floating_cells_.push_back(c);
  }
  isolated_cells_.clear();
  shared_cells_.clear();
  for (long c : floating_cells_) (comp_count_[comp_[c]] == 1.0 ? isolated_cells_ : shared_cells_).push_back(c);
  std::vector<int> shared_id(n_floating_, -1);
  shared_comp_.clear();
  shared_count_.clear();
  for (long c : shared_cells_) {
    int& s = shared_id[comp_[c]];
    if (s < 0) s = static_cast<int>(shared_count_.size()), shared_count_.push_back(comp_count_[comp_[c]]);
    shared_comp_.push_back(s);
  }
}

void Poisson7::project_floating(double* v, bool zero_outside) const {
  if (n_floating_ == 0) return;
  // One-cell components: v - mean(v) = v - v = 0.
  const std::vector<long>& iso = zero_outside ? isolated_active_ : isolated_cells_;
  const long I = static_cast<long>(iso.size());
#pragma omp parallel for schedule(static) if (I >= kParallelMin)
  for (long q = 0; q < I; ++q) v[iso[q]] = 0.0;
  const long M = static_cast<long>(shared_cells_.size());
  if (M == 0) return;
  std::vector<double> sum(shared_count_.size(), 0.0);
  for (long q = 0; q < M; ++q) sum[shared_comp_[q]] += v[shared_cells_[q]];  // ascending cell order
  for (size_t s = 0; s < sum.size(); ++s) sum[s] /= shared_count_[s];
#pragma omp parallel for schedule(static) if (M >= kParallelMin)
  for (long q = 0; q < M; ++q) v[shared_cells_[q]] -= sum[shared_comp_[q]];
}

void Poisson7::gauss_seidel_color(const double* b, double* x, int color, double omega) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const long plane = long(nx) * ny;
  // An odd periodic y or z axis makes rows 0 and n-1 hold neighbouring cells of one colour:
  // then sweep serially, so the result stays independent of the thread count.
  const bool odd_wrap = (periodic(1) && ny % 2) || (periodic(2) && nz % 2);
#pragma omp parallel for collapse(2) schedule(static) if (!odd_wrap && plane * nz >= kParallelMin)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) gs_row(b, x, j, k, color, omega);
}

void Poisson7::gauss_seidel_pair(const double* b, double* x, int first, double omega) const {
  const int ny = g_.ny, nz = g_.nz;
  const long plane = long(g_.nx) * ny;
  const bool odd_wrap = (periodic(1) && ny % 2) || (periodic(2) && nz % 2);
  if (odd_wrap || periodic(2) || nz < 4) {  // plane 0 and nz-1 are neighbours: two plain sweeps
    gauss_seidel_color(b, x, first, omega);
    gauss_seidel_color(b, x, 1 - first, omega);
    return;
  }
  const int second = 1 - first;
  auto plane_sweep = [&](int k, int color) {
    for (int j = 0; j < ny; ++j) gs_row(b, x, j, k, color, omega);
  };
#pragma omp parallel if (plane * nz >= kParallelMin)
  {
    const int nth = omp_get_num_threads(), tid = omp_get_thread_num();
    const int ka = int(long(nz) * tid / nth), kb = int(long(nz) * (tid + 1) / nth);
    for (int k = ka; k < kb; ++k) {
      plane_sweep(k, first);
      if (k - 1 > ka && k - 1 < kb - 1) plane_sweep(k - 1, second);
    }
#pragma omp barrier
    if (kb > ka) plane_sweep(ka, second);
    if (kb - 1 > ka) plane_sweep(kb - 1, second);
  }
}

// One colour of row (j, k): x_c = (b_c + sum_nb w_f x_nb) / D_c (over-relaxed if omega != 1).
void Poisson7::gs_row(const double* b, double* x, int j, int k, int color, double omega) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const bool px = periodic(0), py = periodic(1), pz = periodic(2);
    {
      const long c0 = long(nx) * (j + long(ny) * k);
      double* xr = x + c0;
      const double* br = b + c0;
      const double* d = diag_.data() + c0;
      const double* wxr = wx_.data() + long(nx + 1) * (j + long(ny) * k);
      const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
          row_neighbours<double>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py, pz);
      // A periodic axis of odd length breaks the colouring at the wrap; the sweep stays a
      // fixed, thread-independent sequence but is then only approximately red-black.
      for (int i = (j + k + color) & 1; i < nx; i += 2) {
        if (d[i] <= 0) continue;
        double s = br[i] + ws[i] * xs[i] + wn[i] * xn[i] + wb[i] * xb[i] + wt[i] * xt[i];
        if (i > 0) s += wxr[i] * xr[i - 1]; else if (px) s += wxr[0] * xr[nx - 1];
        if (i < nx - 1) s += wxr[i + 1] * xr[i + 1]; else if (px) s += wxr[0] * xr[0];
        xr[i] = omega == 1.0 ? s / d[i] : xr[i] + omega * (s / d[i] - xr[i]);
      }
    }
}

template <bool kResidual>
void Poisson7::apply_rows(const double* x, double* y, const double* b, double* row_dot) const {
  const int nx = g_.nx, ny = g_.ny, nz = g_.nz;
  const bool px = periodic(0), py = periodic(1), pz = periodic(2);
  const long plane = long(nx) * ny;
  // One row: A x on its active segments (y = 0, or b, in the gaps and outside). A segment's
  // end cells lose the x-neighbour term across the gap, whose face weight is 0: the sums are
  // those of the whole row up to the sign of a zero. px: segments are whole rows (wrap below).
  auto row = [&](int r) {
    const int j = r % ny, k = r / ny;
    const long c0 = long(nx) * r;
    const double* xr = x + c0;
    double* yr = y + c0;
    const double* d = diag_.data() + c0;
    const double* wxr = wx_.data() + long(nx + 1) * r;
    // Neighbour rows; a missing neighbour points at the own row with a zero face weight.
    const auto [xs, xn, xb, xt, ws, wn, wb, wt] =
        row_neighbours<double>(xr, wy_.data(), wz_.data(), nx, ny, nz, j, k, py, pz);
    const double* br = kResidual ? b + c0 : nullptr;
    auto outside = [&](int a, int e) {
      for (int i = a; i < e; ++i) yr[i] = kResidual ? br[i] : 0.0;
    };
    int done = 0;
    double s = 0;
    for (int q = active_.begin(r); q < active_.end(r); ++q) {
      const int lo = active_.lo(q), m = active_.hi(q) - lo;
      outside(done, lo);
      apply_interior(m, d + lo, xr + lo, wxr + lo, ws + lo, wn + lo, wb + lo, wt + lo, xs + lo, xn + lo, xb + lo,
                     xt + lo, yr + lo);
      if (px) {  // wrap face 0 joins cell nx-1 and cell 0 (the segment is the whole row)
        yr[0] -= wxr[0] * xr[nx - 1];
        yr[nx - 1] -= wxr[0] * xr[0];
      }
      if constexpr (kResidual)
        for (int i = lo; i < lo + m; ++i) yr[i] = br[i] - yr[i];
      if (row_dot)
        for (int i = lo; i < lo + m; ++i) s += xr[i] * yr[i];
      done = lo + m;
    }
    outside(done, nx);
    if (row_dot) row_dot[r] = s;
  };
#pragma omp parallel if (plane * nz >= kParallelMin)
  {
    int r0, r1;
    active_.share(omp_get_thread_num(), omp_get_num_threads(), r0, r1);
    for (int r = r0; r < r1; ++r) row(r);
  }
}

void Poisson7::apply(const double* x, double* y) const { apply_rows<false>(x, y, nullptr); }

double Poisson7::apply_dot(const double* x, double* y) const {
  row_dot_.resize(long(g_.ny) * g_.nz);
  apply_rows<false>(x, y, nullptr, row_dot_.data());
  double s = 0;
  for (double v : row_dot_) s += v;
  return s;
}

// r = b - A x, row by row right after A x (the same arithmetic as apply, then b - y).
void Poisson7::residual(const double* b, const double* x, double* r) const { apply_rows<true>(x, r, b); }

}  // namespace cgdem::pressure
