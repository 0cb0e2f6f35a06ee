// FFTW fast Poisson preconditioner; see fft_preconditioner.hpp.
#include "solvers/pressure/fft_preconditioner.hpp"

#include <fftw3.h>
#include <omp.h>

#include <cmath>
#include <mutex>

#include "core/error.hpp"
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

namespace {
constexpr long kMeasureCells = 1L << 17;

struct AxisKind {
  fftw_r2r_kind fwd, bwd;
  double norm;                 // forward+backward multiply by this
  std::vector<double> lambda;  // (2 - 2 cos theta_m) / h^2
};

AxisKind axis_kind(Boundary lo, Boundary hi, int n, double h) {
  AxisKind a;
  a.lambda.resize(n);
  a.norm = 2.0 * n;
  double shift = 0, period = M_PI;
  if (lo == Boundary::Periodic) {
    a.fwd = FFTW_R2HC; a.bwd = FFTW_HC2R; a.norm = n;
  } else if (lo == Boundary::Wall && hi == Boundary::Wall) {
    a.fwd = FFTW_REDFT10; a.bwd = FFTW_REDFT01;
  } else if (lo == Boundary::Open && hi == Boundary::Open) {
    a.fwd = FFTW_RODFT10; a.bwd = FFTW_RODFT01; shift = 1;
  } else if (lo == Boundary::Wall) {
    a.fwd = a.bwd = FFTW_REDFT11; shift = 0.5;
  } else {
    a.fwd = a.bwd = FFTW_RODFT11; shift = 0.5;
  }
  for (int m = 0; m < n; ++m) {
    const double theta = (lo == Boundary::Periodic) ? 2 * M_PI * std::min(m, n - m) / n
                                                    : period * (m + shift) / n;
    a.lambda[m] = (2 - 2 * std::cos(theta)) / (h * h);
  }
  return a;
}

std::mutex& planner_mutex() {  // the FFTW planner is not thread-safe
  static std::mutex m;
  return m;
}
}  // namespace

struct FftPreconditioner::Plans {
  fftw_plan fwd = nullptr, bwd = nullptr;
  double* buf = nullptr;
  ~Plans() {
    std::lock_guard<std::mutex> lock(planner_mutex());
    if (fwd) fftw_destroy_plan(fwd);
    if (bwd) fftw_destroy_plan(bwd);
    if (buf) fftw_free(buf);
  }
};

FftPreconditioner::FftPreconditioner(const GridSpec& g, Scaling s)
    : g_(g), scaling_(s), plans_(std::make_unique<Plans>()) {
  const AxisKind kx = axis_kind(g.bc[0], g.bc[1], g.nx, g.dx);
  const AxisKind ky = axis_kind(g.bc[2], g.bc[3], g.ny, g.dy);
  const AxisKind kz = axis_kind(g.bc[4], g.bc[5], g.nz, g.dz);
  const long n = g.cells();
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    static std::once_flag threads_once;
    std::call_once(threads_once, [] { fftw_init_threads(); });
    // Small grids: measuring costs more than it saves, and threads do not pay.
    const bool small = n < kMeasureCells;
    const unsigned flags = small ? FFTW_ESTIMATE : FFTW_MEASURE;
    fftw_plan_with_nthreads(small ? 1 : omp_get_max_threads());
    plans_->buf = fftw_alloc_real(n);
    // Row-major FFTW order: z slowest, x fastest, matching cell index i + nx*(j + ny*k).
    plans_->fwd = fftw_plan_r2r_3d(g.nz, g.ny, g.nx, plans_->buf, plans_->buf, kz.fwd, ky.fwd, kx.fwd, flags);
    plans_->bwd = fftw_plan_r2r_3d(g.nz, g.ny, g.nx, plans_->buf, plans_->buf, kz.bwd, ky.bwd, kx.bwd, flags);
  }
  if (!plans_->fwd || !plans_->bwd) throw Error("pressure: FFTW could not plan the fast Poisson solve");
  inv_lambda_.resize(n);
  const double norm = kx.norm * ky.norm * kz.norm;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double lam = kx.lambda[i] + ky.lambda[j] + kz.lambda[k];
        // The null mode of a singular L (lambda = 0 exactly for m = 0) is dropped.
        inv_lambda_[i + long(g.nx) * (j + long(g.ny) * k)] = lam > 0 ? 1.0 / (lam * norm) : 0.0;
      }
}

FftPreconditioner::~FftPreconditioner() = default;

void FftPreconditioner::setup(const Poisson7& op) {
  const long n = op.n();
  dscale_.resize(n);
  const double dL = 2 / (g_.dx * g_.dx) + 2 / (g_.dy * g_.dy) + 2 / (g_.dz * g_.dz);
  const auto& D = op.diag();
  for (long c = 0; c < n; ++c) {
    if (D[c] <= 0) dscale_[c] = 0;  // isolated cell
    else dscale_[c] = scaling_ == Scaling::Diagonal ? std::sqrt(dL / D[c]) : 1.0;
  }
}

void FftPreconditioner::apply(const double* r, double* z) {
  const long n = g_.cells();
  double* b = plans_->buf;
  const double* s = dscale_.data();
  const double* il = inv_lambda_.data();
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long c = 0; c < n; ++c) b[c] = s[c] * r[c];
  fftw_execute(plans_->fwd);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long c = 0; c < n; ++c) b[c] *= il[c];
  fftw_execute(plans_->bwd);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (long c = 0; c < n; ++c) z[c] = s[c] * b[c];
}

}  // namespace cgdem::pressure
