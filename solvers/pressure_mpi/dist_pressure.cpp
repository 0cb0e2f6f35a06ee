// Distributed PCG pressure solve; see dist_pressure.hpp.
#include "solvers/pressure_mpi/dist_pressure.hpp"

#include <nvector/nvector_parallel.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_pcg.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "parallel/mpi/halo.hpp"
#include "solvers/pressure_mpi/pfmg.hpp"
#include "core/error.hpp"
#include "solvers/pressure/fft_preconditioner.hpp"
#include "solvers/pressure/multigrid.hpp"
#include "solvers/pressure/poisson7.hpp"

namespace cgdem::air_mpi {

using pressure::Boundary;

namespace {

// Block Jacobi: a serial preconditioner on the diagonal block A_bb of each rank (see the header).
class BlockJacobi : public DistPreconditioner {
 public:
  enum class Kind { Multigrid, Multigrid2, Fft };
  BlockJacobi(const DistPoisson& op, Kind kind) : spec_(op.local_spec(Boundary::Open)), local_(spec_) {
    using Mg = pressure::MultigridPreconditioner;
    using Fft = pressure::FftPreconditioner;
    if (kind == Kind::Fft) prec_ = std::make_unique<Fft>(spec_, Fft::Scaling::Diagonal);
    else prec_ = std::make_unique<Mg>(spec_, kind == Kind::Multigrid2 ? 2 : 1, Mg::Precision::Single);
  }
  void setup(DistPoisson& op) override {
    const GridBlocks& b = op.blocks();
    const auto e = b.local_cells();
    std::vector<double> a[3] = {op.ax(), op.ay(), op.az()};
    // Half the coefficient on the cut faces: the Open term 2 a/h^2 then equals the dropped
    // coupling's a/h^2 on the diagonal.
    for (int ax = 0; ax < 3; ++ax) {
      std::array<long, 3> f{e[0], e[1], e[2]};
      f[ax] += 1;
      for (int h = 0; h < 2; ++h) {
        if (!b.is_cut(2 * ax + h)) continue;
        const long m = h ? f[ax] - 1 : 0;
        for (long k = 0; k < f[2]; ++k)
          for (long j = 0; j < f[1]; ++j)
            for (long i = 0; i < f[0]; ++i) {
              const long idx[3] = {i, j, k};
              if (idx[ax] == m) a[ax][i + f[0] * (j + f[1] * k)] *= 0.5;
            }
      }
    }
    local_.set(a[0], a[1], a[2]);
    prec_->setup(local_);
  }
  void apply(const double* r, double* z) override { prec_->apply(r, z); }

 private:
  pressure::GridSpec spec_;
  pressure::Poisson7 local_;
  std::unique_ptr<pressure::Preconditioner> prec_;
};

// Additive Schwarz with an overlap of kGhost cells: each rank solves (one multigrid V-cycle,
// as bj-mg) on its block grown by kGhost cells on every cut side, the principal submatrix of A
// on those cells (the faces leaving the grown block keep their weight on the diagonal: the
// Open-side trick of BlockJacobi), with the residual there from the neighbours (one halo
// exchange); the grown parts of the result are added back to the blocks that own those
// cells (reverse_add). z = sum_i R_i^T M_i R_i r is symmetric when each M_i is, as PCG needs.
// Compared with block Jacobi the blocks see their neighbours' residual next to the cut.
class AdditiveSchwarz : public DistPreconditioner {
 public:
  AdditiveSchwarz(const DistPoisson& op, int nu) : halo_(op.comm(), op.blocks()), blocks_(op.blocks()) {
    const auto e = blocks_.local_cells();
    spec_ = op.local_spec(Boundary::Open);
    for (int a = 0; a < 3; ++a) {
      lo_[a] = blocks_.is_cut(2 * a) ? fluid::kGhost : 0;
      hi_[a] = blocks_.is_cut(2 * a + 1) ? fluid::kGhost : 0;
      n_[a] = e[a] + lo_[a] + hi_[a];
    }
    spec_.nx = n_[0], spec_.ny = n_[1], spec_.nz = n_[2];
    local_ = std::make_unique<pressure::Poisson7>(spec_);
    mg_ = std::make_unique<pressure::MultigridPreconditioner>(spec_, nu, pressure::MultigridPreconditioner::Precision::Single);
    cells_ = fluid::Field(e);
    rg_.resize(static_cast<size_t>(n_[0]) * n_[1] * n_[2]);
    zg_.resize(rg_.size());
  }
  void setup(DistPoisson& op) override {
    const auto e = blocks_.local_cells();
    const std::vector<double>* a[3] = {&op.ax(), &op.ay(), &op.az()};
    std::vector<double> grown[3];
    for (int d = 0; d < 3; ++d) {
      // The block's faces with the neighbours' faces beyond the cuts (halo exchange).
      std::array<int, 3> fe = e;
      fe[d] += 1;
      fluid::Field f(fe);
      to_field(a[d]->data(), fe, {0, 0, 0}, f);
      halo_.exchange(f, d);
      std::array<int, 3> ge = n_;
      ge[d] += 1;
      grown[d].resize(static_cast<size_t>(ge[0]) * ge[1] * ge[2]);
      for (int k = 0; k < ge[2]; ++k)
        for (int j = 0; j < ge[1]; ++j)
          for (int i = 0; i < ge[0]; ++i) {
            const int q[3] = {i - lo_[0], j - lo_[1], k - lo_[2]};
            double v = f(q[0], q[1], q[2]);
            // A face on the grown block's boundary beyond a cut: half its weight (Open trick).
            const int m[3] = {i, j, k};
            if ((m[d] == 0 && lo_[d] > 0) || (m[d] == ge[d] - 1 && hi_[d] > 0)) v *= 0.5;
            grown[d][i + static_cast<long>(ge[0]) * (j + static_cast<long>(ge[1]) * k)] = v;
          }
    }
    local_->set(grown[0], grown[1], grown[2]);
    mg_->setup(*local_);
  }
  void apply(const double* r, double* z) override {
    const auto e = blocks_.local_cells();
    to_field(r, e, {0, 0, 0}, cells_);
    halo_.exchange(cells_, kCellCentred);
    from_field(cells_, n_, lo_, rg_.data());
    mg_->apply(rg_.data(), zg_.data());
    cells_.fill(0.0);
    to_field(zg_.data(), n_, lo_, cells_);
    halo_.reverse_add(cells_, kCellCentred);
    from_field(cells_, e, {0, 0, 0}, z);
  }

 private:
  // A flat array over n cells (x fastest) to and from the field's cells starting at -lo
  // (which reach into its ghost layers when lo > 0).
  static void to_field(const double* v, const std::array<int, 3>& n, const std::array<int, 3>& lo, fluid::Field& f) {
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          f(i - lo[0], j - lo[1], k - lo[2]) = v[i + static_cast<long>(n[0]) * (j + static_cast<long>(n[1]) * k)];
  }
  static void from_field(const fluid::Field& f, const std::array<int, 3>& n, const std::array<int, 3>& lo, double* v) {
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          v[i + static_cast<long>(n[0]) * (j + static_cast<long>(n[1]) * k)] = f(i - lo[0], j - lo[1], k - lo[2]);
  }
  Halo halo_;
  GridBlocks blocks_;
  pressure::GridSpec spec_;
  std::array<int, 3> lo_{}, hi_{}, n_{};
  std::unique_ptr<pressure::Poisson7> local_;
  std::unique_ptr<pressure::MultigridPreconditioner> mg_;
  fluid::Field cells_;
  std::vector<double> rg_, zg_;
};

// Identity: plain CG through the same driver.
class NoPreconditioner : public DistPreconditioner {
 public:
  explicit NoPreconditioner(long n) : n_(n) {}
  void setup(DistPoisson&) override {}
  void apply(const double* r, double* z) override { std::copy(r, r + n_, z); }

 private:
  long n_;
};

// The global dot product: the local part with the fixed blocking of pressure::dot (the stock
// N_VDotProd_Parallel's single running sum took half the time of a solve on one rank), then
// the sum over the ranks.
realtype dot_global(N_Vector a, N_Vector b) {
  double s = pressure::dot(N_VGetArrayPointer_Parallel(a), N_VGetArrayPointer_Parallel(b),
                           N_VGetLocalLength_Parallel(a));
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, NV_COMM_P(a));
  return s;
}

}  // namespace

std::unique_ptr<DistPreconditioner> make_dist_preconditioner(const std::string& name, const DistPoisson& op) {
  if (name == "none") return std::make_unique<NoPreconditioner>(op.n());
  if (name == "bj-mg") return std::make_unique<BlockJacobi>(op, BlockJacobi::Kind::Multigrid);
  if (name == "bj-mg2") return std::make_unique<BlockJacobi>(op, BlockJacobi::Kind::Multigrid2);
  if (name == "bj-fft") return std::make_unique<BlockJacobi>(op, BlockJacobi::Kind::Fft);
  if (name == "as-mg") return std::make_unique<AdditiveSchwarz>(op, 1);
  if (name == "as-mg2") return std::make_unique<AdditiveSchwarz>(op, 2);
  if (name == "pfmg") return make_pfmg_preconditioner(op);
  throw Error("air pressure: unknown distributed preconditioner '" + name +
              "' (known: none, bj-mg, bj-mg2, bj-fft, as-mg, as-mg2, pfmg)");
}

// SUNLinSol_PCG on parallel NVECTORs wrapping the caller's arrays.
struct DistPressureSolver::Pcg {
  SUNContext ctx = nullptr;
  N_Vector xv = nullptr, bv = nullptr;
  SUNLinearSolver ls = nullptr;
  DistPressureSolver* owner = nullptr;
  MPI_Comm comm;

  Pcg(DistPressureSolver* s, MPI_Comm c, long n, long global_n) : owner(s), comm(c) {
    if (SUNContext_Create(&comm, &ctx) != 0) throw Error("air pressure: SUNContext_Create failed");
    xv = N_VMake_Parallel(comm, n, global_n, nullptr, ctx);
    bv = N_VMake_Parallel(comm, n, global_n, nullptr, ctx);
    // PCG clones its work vectors from a template that owns its data.
    N_Vector tmpl = N_VNew_Parallel(comm, n, global_n, ctx);
    if (!xv || !bv || !tmpl) throw Error("air pressure: N_VNew_Parallel failed (do the local lengths add up?)");
    for (N_Vector v : {xv, bv, tmpl}) v->ops->nvdotprod = dot_global;
    ls = SUNLinSol_PCG(tmpl, SUN_PREC_LEFT, 100, ctx);
    N_VDestroy(tmpl);
    if (!xv || !bv || !ls) throw Error("air pressure: creating the SUNDIALS PCG on parallel vectors failed");
    SUNLinSolSetATimes(ls, this, atimes);
    SUNLinSolSetPreconditioner(ls, this, nullptr, psolve);
    if (SUNLinSolInitialize(ls) != 0) throw Error("air pressure: SUNLinSolInitialize (PCG) failed");
  }
  ~Pcg() {
    SUNLinSolFree(ls);
    N_VDestroy(xv);
    N_VDestroy(bv);
    SUNContext_Free(&ctx);
  }
  static int atimes(void* self, N_Vector v, N_Vector z) {
    auto* me = static_cast<Pcg*>(self);
    me->owner->op_.apply(N_VGetArrayPointer_Parallel(v), N_VGetArrayPointer_Parallel(z));
    return 0;
  }
  static int psolve(void* self, N_Vector r, N_Vector z, realtype, int) {
    auto* me = static_cast<Pcg*>(self);
    double* zd = N_VGetArrayPointer_Parallel(z);
    me->owner->prec_->apply(N_VGetArrayPointer_Parallel(r), zd);
    me->owner->op_.project_floating(zd);  // keeps M symmetric on the mean-free subspace
    return 0;
  }
};

DistPressureSolver::DistPressureSolver(MPI_Comm comm, const GridBlocks& blocks, const pressure::GridSpec& global,
                                       const DistOptions& opt)
    : opt_(opt), op_(comm, blocks, global) {
  if (!(opt.rel_tol > 0) || opt.max_iter < 1) throw Error("air pressure: rel_tol must be > 0 and max_iter >= 1");
  prec_ = make_dist_preconditioner(opt.preconditioner, op_);
  pcg_ = std::make_unique<Pcg>(this, comm, op_.n(), op_.global_n());
}

DistPressureSolver::~DistPressureSolver() = default;

void DistPressureSolver::set_coefficients(const std::vector<double>& ax, const std::vector<double>& ay,
                                          const std::vector<double>& az) {
  op_.set(ax, ay, az);
  prec_->setup(op_);
  have_coef_ = true;
}

void DistPressureSolver::set_rel_tol(double rel_tol) {
  if (!(rel_tol > 0)) throw Error("air pressure: rel_tol must be > 0");
  opt_.rel_tol = rel_tol;
}

pressure::SolveStats DistPressureSolver::solve(const std::vector<double>& rhs, std::vector<double>& phi) {
  if (!have_coef_) throw Error("air pressure: solve() called before set_coefficients()");
  const long n = op_.n();
  int ok = long(rhs.size()) == n && long(phi.size()) == n;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, op_.comm());
  if (!ok)
    throw Error(fmt::format("air pressure: rhs and phi need the block's cells ({} on this rank; got {} and {}, or "
                            "wrong sizes on another rank)",
                            n, rhs.size(), phi.size()));
  const double t0 = MPI_Wtime();
  b_.resize(n);
  r_.resize(n);
  for (long c = 0; c < n; ++c) b_[c] = -rhs[c];  // div(a grad phi) = rhs  <=>  A phi = -rhs
  op_.project_floating(b_.data());
  auto global_norm = [&](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, op_.comm());
    return std::sqrt(s);
  };
  const double bnorm = global_norm(b_);
  pressure::SolveStats st;
  if (bnorm == 0) {
    std::fill(phi.begin(), phi.end(), 0.0);
    st.converged = true;
    st.seconds = MPI_Wtime() - t0;
    return st;
  }
  int zero_guess = std::all_of(phi.begin(), phi.end(), [](double v) { return v == 0.0; });
  MPI_Allreduce(MPI_IN_PLACE, &zero_guess, 1, MPI_INT, MPI_LAND, op_.comm());
  auto& p = *pcg_;
  N_VSetArrayPointer_Parallel(b_.data(), p.bv);
  N_VSetArrayPointer_Parallel(phi.data(), p.xv);
  SUNLinSol_PCGSetMaxl(p.ls, opt_.max_iter);
  SUNLinSolSetZeroGuess(p.ls, zero_guess ? SUNTRUE : SUNFALSE);
  const int flag = SUNLinSolSolve(p.ls, nullptr, p.xv, p.bv, opt_.rel_tol * bnorm);
  if (flag < 0) throw Error(fmt::format("air pressure: SUNLinSol_PCG failed with flag {}", flag));
  op_.project_floating(phi.data());
  op_.apply(phi.data(), r_.data());
  for (long c = 0; c < n; ++c) r_[c] = b_[c] - r_[c];
  st.iterations = SUNLinSolNumIters(p.ls);
  st.rel_residual = global_norm(r_) / bnorm;
  // The recurrence residual may drift from the true one; report the true one and require both.
  st.converged = flag == SUNLS_SUCCESS && st.rel_residual <= 10 * opt_.rel_tol;
  st.seconds = MPI_Wtime() - t0;
  return st;
}

}  // namespace cgdem::air_mpi
