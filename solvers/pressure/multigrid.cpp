// Multigrid V-cycle preconditioner; see multigrid.hpp.
#include "solvers/pressure/multigrid.hpp"

#include <omp.h>

#include <algorithm>

namespace cgdem::pressure {

namespace {
// Coarse face coefficients normal to `axis`: mean of the fine faces each coarse face covers
// (the fine face plane 2C along the axis, capped at the last one; 2 x 2 fine faces across it,
// fewer at an odd edge), summed in the order k, j, i.
std::vector<double> coarsen_faces(const GridSpec& f, const GridSpec& c, const std::vector<double>& a, int axis) {
  const int nf[3] = {f.nx, f.ny, f.nz}, nc[3] = {c.nx, c.ny, c.nz};
  long ef[3] = {nf[0], nf[1], nf[2]}, ec[3] = {nc[0], nc[1], nc[2]};
  ef[axis] += 1;
  ec[axis] += 1;
  std::vector<double> out(ec[0] * ec[1] * ec[2]);
  // The fine indices a coarse index C covers along axis d: one plane, or 2C and 2C + 1.
  auto range = [&](int d, long C, long& lo, long& hi) {
    if (d == axis) lo = hi = std::min<long>(2 * C, nf[d]);
    else lo = 2 * C, hi = std::min<long>(2 * C + 1, nf[d] - 1);
  };
#pragma omp parallel for collapse(2) schedule(static) if (long(out.size()) >= kParallelMin)
  for (long K = 0; K < ec[2]; ++K)
    for (long J = 0; J < ec[1]; ++J) {
      long k0, k1, j0, j1;
      range(2, K, k0, k1);
      range(1, J, j0, j1);
      double* o = out.data() + ec[0] * (J + ec[1] * K);
      for (long I = 0; I < ec[0]; ++I) {
        long i0, i1;
        range(0, I, i0, i1);
        const int cnt = int((k1 - k0 + 1) * (j1 - j0 + 1) * (i1 - i0 + 1));
        double s = 0;
        for (long k = k0; k <= k1; ++k)
          for (long j = j0; j <= j1; ++j) {
            const double* row = a.data() + ef[0] * (j + ef[1] * k);
            s += row[i0];
            if (i1 > i0) s += row[i1];
          }
        o[I] = s / cnt;
      }
    }
  return out;
}

bool can_coarsen(const GridSpec& g) {
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 4) return false;
    if (g.bc[2 * d] == Boundary::Periodic && n[d] % 2) return false;
  }
  return g.cells() > MultigridPreconditioner::kCoarsestCells;
}
}  // namespace

MultigridPreconditioner::MultigridPreconditioner(const GridSpec& fine, int nu, Precision prec, Cycle cycle,
                                                 double omega, bool skip_blocked)
    : nu_(nu), precision_(prec), cycle_(cycle), omega_(omega), skip_blocked_(skip_blocked) {
  grids_.push_back(fine);
  while (can_coarsen(grids_.back())) {
    GridSpec c = grids_.back();
    c.nx = (c.nx + 1) / 2; c.ny = (c.ny + 1) / 2; c.nz = (c.nz + 1) / 2;
    c.dx *= 2; c.dy *= 2; c.dz *= 2;
    grids_.push_back(c);
  }
  lv_.resize(grids_.size());
  for (size_t l = 0; l < grids_.size(); ++l) {
    const long n = grids_[l].cells();
    const bool dbl = precision_ == Precision::Double, last = l + 1 == grids_.size();
    if (dbl || last) {
      lv_[l].b.resize(n);
      lv_[l].x.resize(n);
    }
    if (dbl) lv_[l].r.resize(n);
    if (!dbl) {
      lv_[l].bf.resize(n);
      lv_[l].xf.resize(n);
    }
    if (l > 0) lv_[l].own = std::make_unique<Poisson7>(grids_[l]);
  }
}

MultigridPreconditioner::~MultigridPreconditioner() = default;

void MultigridPreconditioner::setup(const Poisson7& op) {
  lv_[0].op = &op;
  for (size_t l = 1; l < lv_.size(); ++l) {
    const Poisson7& f = *lv_[l - 1].op;
    lv_[l].own->set(coarsen_faces(grids_[l - 1], grids_[l], f.ax(), 0),
                    coarsen_faces(grids_[l - 1], grids_[l], f.ay(), 1),
                    coarsen_faces(grids_[l - 1], grids_[l], f.az(), 2));
    lv_[l].op = lv_[l].own.get();
  }
  if (coarse_)
    coarse_->refactor(*lv_.back().op);  // keeps the analysis while the pattern is the same
  else
    coarse_ = std::make_unique<CholmodFactor>(*lv_.back().op);
  if (precision_ == Precision::Single) {
    scale_ = stencil32_scale(op);
    // Skipping (stencil32.hpp): the finest level visits op.active() (D > 0; apply() writes z = 0
    // on the other cells), each coarser level but the coarsest (solved whole) the parents of
    // the cells the level below visits. A coarse cell with D > 0 has a fine child with D > 0,
    // and one left out has b = 0 (its children's residuals were left out). These sets follow
    // from the finest one alone: rebuilt when it changes.
    const size_t L = lv_.size();
    const bool skip = skip_blocked_ && L > 1;
    if (skip && !(fine_seen_ == op.active())) {
      for (size_t l = 1; l + 1 < L; ++l) {
        const GridSpec& g = grids_[l];
        std::vector<unsigned char> mask(g.cells(), 0);
        (l == 1 ? op.active() : lv_[l - 1].act).mark_parents(mask.data());
        lv_[l].act.from_mask(mask.data(), g.nx, g.ny, g.nz, g.bc[0] == Boundary::Periodic);
      }
      fine_seen_ = op.active();
    }
    for (size_t l = 0; l < L; ++l) {
      const ActiveRows* act = !skip || l + 1 == L ? nullptr : l == 0 ? &op.active() : &lv_[l].act;
      lv_[l].s32.set(*lv_[l].op, scale_, omega_, act);
    }
  }
}

void MultigridPreconditioner::apply(const double* rin, double* z) {
  if (precision_ == Precision::Double) {
    b0_ = rin, x0_ = z;  // level 0 works in place on the caller's arrays
    vcycle(0, true);
    return;
  }
  // r to float and z = s x back, on the finest level's active segments; z = 0 elsewhere (where
  // the whole cycle gives 0 up to the sign: D = 0 and b = 0 there, stencil32.hpp).
  const ActiveRows& act = lv_[0].s32.active();
  const int nx = grids_[0].nx;
  float* bf = lv_[0].bf.data();
  auto rows = [&](auto&& row) {
#pragma omp parallel if (grids_[0].cells() >= kParallelMin)
    {
      int r0, r1;
      act.share(omp_get_thread_num(), omp_get_num_threads(), r0, r1);
      for (int r = r0; r < r1; ++r) row(r, long(nx) * r);
    }
  };
  rows([&](int r, long c0) {
    for (int q = act.begin(r); q < act.end(r); ++q)
      for (long c = c0 + act.lo(q); c < c0 + act.hi(q); ++c) bf[c] = static_cast<float>(rin[c]);
  });
  vcycle32(0, true);
  const float* xf = lv_[0].xf.data();
  const double s = scale_;
  rows([&](int r, long c0) {
    long done = c0;
    for (int q = act.begin(r); q < act.end(r); ++q) {
      std::fill(z + done, z + c0 + act.lo(q), 0.0);
      for (long c = c0 + act.lo(q); c < c0 + act.hi(q); ++c) z[c] = s * static_cast<double>(xf[c]);
      done = c0 + act.hi(q);
    }
    std::fill(z + done, z + c0 + nx, 0.0);
  });
}

// The cycle of multigrid.hpp on the float operators (which are scale_ A).
void MultigridPreconditioner::vcycle32(int l, bool from_zero) {
  Level& L = lv_[l];
  if (l == levels() - 1) {  // coarsest (only ever from zero): (s A)^{-1} b = A^{-1} b / s, in double
    const long n = static_cast<long>(L.b.size());
    for (long c = 0; c < n; ++c) L.b[c] = L.bf[c];
    coarse_->solve(L.b.data(), L.x.data());
    for (long c = 0; c < n; ++c) L.xf[c] = static_cast<float>(L.x[c] / scale_);
    return;
  }
  const Stencil32& S = L.s32;
  float *b = L.bf.data(), *x = L.xf.data();
  for (int s = 0; s < nu_; ++s) S.gs_pair(b, x, 0, from_zero && s == 0);  // the first pair may start from x = 0
  Level& C = lv_[l + 1];
  S.restrict_residual(b, x, grids_[l + 1], C.bf.data());
  vcycle32(l + 1, true);
  if (cycle_ == Cycle::W && l + 2 < levels()) vcycle32(l + 1, false);  // the coarsest solve is exact: once
  S.prolong_add(grids_[l + 1], C.xf.data(), x);
  for (int s = 0; s < nu_; ++s) S.gs_pair(b, x, 1, false);
}

void MultigridPreconditioner::vcycle(int l, bool from_zero) {
  Level& L = lv_[l];
  const double* b = l == 0 ? b0_ : L.b.data();
  double* x = l == 0 ? x0_ : L.x.data();
  const long n = static_cast<long>(L.r.size());
  if (l == levels() - 1) {
    coarse_->solve(b, x);
    return;
  }
  const Poisson7& A = *L.op;
  if (from_zero) std::fill(x, x + n, 0.0);
  for (int s = 0; s < nu_; ++s) A.gauss_seidel_pair(b, x, 0, omega_);
  A.residual(b, x, L.r.data());
  // Restriction R = P^T / 8 onto level l+1.
  const GridSpec &f = grids_[l], &c = grids_[l + 1];
  Level& C = lv_[l + 1];
  std::fill(C.b.begin(), C.b.end(), 0.0);
#pragma omp parallel for collapse(2) schedule(static) if (f.cells() >= kParallelMin)
  for (int K = 0; K < c.nz; ++K)
    for (int J = 0; J < c.ny; ++J)
      for (int I = 0; I < c.nx; ++I) {
        double s = 0;
        for (int k = 2 * K; k <= std::min(2 * K + 1, f.nz - 1); ++k)
          for (int j = 2 * J; j <= std::min(2 * J + 1, f.ny - 1); ++j)
            for (int i = 2 * I; i <= std::min(2 * I + 1, f.nx - 1); ++i)
              s += L.r[i + long(f.nx) * (j + long(f.ny) * k)];
        C.b[I + long(c.nx) * (J + long(c.ny) * K)] = s / 8;
      }
  vcycle(l + 1, true);
  if (cycle_ == Cycle::W && l + 2 < levels()) vcycle(l + 1, false);
  // Prolongation: piecewise constant.
#pragma omp parallel for collapse(2) schedule(static) if (f.cells() >= kParallelMin)
  for (int k = 0; k < f.nz; ++k)
    for (int j = 0; j < f.ny; ++j) {
      const double* xc = C.x.data() + long(c.nx) * (j / 2 + long(c.ny) * (k / 2));
      double* xf = x + long(f.nx) * (j + long(f.ny) * k);
      for (int i = 0; i < f.nx; ++i) xf[i] += xc[i / 2];
    }
  for (int s = 0; s < nu_; ++s) A.gauss_seidel_pair(b, x, 1, omega_);
}

}  // namespace cgdem::pressure
