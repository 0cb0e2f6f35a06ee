// The hypre PFMG preconditioner; see pfmg.hpp.
#include "solvers/pressure_mpi/pfmg.hpp"

#include "core/error.hpp"

#ifdef CGDEM_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_struct_ls.h>

#include <fmt/format.h>

#include <vector>
#endif

namespace cgdem::air_mpi {

#ifndef CGDEM_HAVE_HYPRE

bool have_pfmg() { return false; }
std::unique_ptr<DistPreconditioner> make_pfmg_preconditioner(const DistPoisson&) {
  throw Error("air pressure: preconditioner 'pfmg' needs hypre (libhypre-dev), which this build did not find");
}

#else

namespace {

void check(HYPRE_Int code, const char* what) {
  if (code != 0) {
    HYPRE_ClearAllErrors();
    throw Error(fmt::format("air pressure: hypre {} failed (error code {})", what, code));
  }
}

class Pfmg : public DistPreconditioner {
 public:
  explicit Pfmg(const DistPoisson& op) : comm_(op.comm()) {
    static bool initialised = false;  // HYPRE_Init once per process (needed since hypre 2.20)
    if (!initialised) {
      HYPRE_Init();
      initialised = true;
    }
    const GridBlocks& b = op.blocks();
    for (int a = 0; a < 3; ++a) lo_[a] = b.lo()[a], hi_[a] = b.hi()[a] - 1;  // hypre boxes are inclusive
    check(HYPRE_StructGridCreate(comm_, 3, &grid_), "StructGridCreate");
    check(HYPRE_StructGridSetExtents(grid_, lo_, hi_), "StructGridSetExtents");
    check(HYPRE_StructGridAssemble(grid_), "StructGridAssemble");
    // Entry 0 the centre, then -x, +x, -y, +y, -z, +z.
    HYPRE_Int off[7][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    check(HYPRE_StructStencilCreate(3, 7, &stencil_), "StructStencilCreate");
    for (int e = 0; e < 7; ++e) check(HYPRE_StructStencilSetElement(stencil_, e, off[e]), "StructStencilSetElement");
    check(HYPRE_StructVectorCreate(comm_, grid_, &b_), "StructVectorCreate");
    check(HYPRE_StructVectorCreate(comm_, grid_, &x_), "StructVectorCreate");
    check(HYPRE_StructVectorInitialize(b_), "StructVectorInitialize");
    check(HYPRE_StructVectorInitialize(x_), "StructVectorInitialize");
    n_ = op.n();
    buf_.resize(n_);
  }
  ~Pfmg() override {
    if (solver_) HYPRE_StructPFMGDestroy(solver_);
    if (A_) HYPRE_StructMatrixDestroy(A_);
    HYPRE_StructVectorDestroy(b_);
    HYPRE_StructVectorDestroy(x_);
    HYPRE_StructStencilDestroy(stencil_);
    HYPRE_StructGridDestroy(grid_);
  }

  void setup(DistPoisson& op) override {
    if (solver_) HYPRE_StructPFMGDestroy(solver_), solver_ = nullptr;
    if (A_) HYPRE_StructMatrixDestroy(A_), A_ = nullptr;
    check(HYPRE_StructMatrixCreate(comm_, grid_, stencil_, &A_), "StructMatrixCreate");
    check(HYPRE_StructMatrixInitialize(A_), "StructMatrixInitialize");
    const auto e = op.blocks().local_cells();
    const long nx = e[0], ny = e[1], nz = e[2];
    const double* wx = op.w(0).data();
    const double* wy = op.w(1).data();
    const double* wz = op.w(2).data();
    const double* d = op.diag().data();
    std::vector<double> v(7 * n_);
    for (long k = 0; k < nz; ++k)
      for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) {
          const long c = i + nx * (j + ny * k);
          const long fx = i + (nx + 1) * (j + ny * k), fy = i + nx * (j + (ny + 1) * k);
          double* row = &v[7 * c];
          row[0] = d[c] > 0 ? d[c] : 1.0;
          row[1] = -wx[fx], row[2] = -wx[fx + 1];
          row[3] = -wy[fy], row[4] = -wy[fy + nx];
          row[5] = -wz[c], row[6] = -wz[c + nx * ny];
        }
    HYPRE_Int entries[7] = {0, 1, 2, 3, 4, 5, 6};
    check(HYPRE_StructMatrixSetBoxValues(A_, lo_, hi_, 7, entries, v.data()), "StructMatrixSetBoxValues");
    check(HYPRE_StructMatrixAssemble(A_), "StructMatrixAssemble");
    check(HYPRE_StructPFMGCreate(comm_, &solver_), "StructPFMGCreate");
    HYPRE_StructPFMGSetMaxIter(solver_, 1);
    HYPRE_StructPFMGSetTol(solver_, 0.0);
    HYPRE_StructPFMGSetZeroGuess(solver_);
    HYPRE_StructPFMGSetRAPType(solver_, 0);
    HYPRE_StructPFMGSetRelaxType(solver_, 1);
    HYPRE_StructPFMGSetNumPreRelax(solver_, 1);
    HYPRE_StructPFMGSetNumPostRelax(solver_, 1);
    HYPRE_StructPFMGSetLogging(solver_, 0);
    check(HYPRE_StructPFMGSetup(solver_, A_, b_, x_), "StructPFMGSetup");
  }

  void apply(const double* r, double* z) override {
    std::copy(r, r + n_, buf_.begin());
    check(HYPRE_StructVectorSetBoxValues(b_, lo_, hi_, buf_.data()), "StructVectorSetBoxValues");
    check(HYPRE_StructVectorAssemble(b_), "StructVectorAssemble");
    // Reaching max_iter = 1 is the normal outcome of one V-cycle, not an error: ignore the code.
    HYPRE_StructPFMGSolve(solver_, A_, b_, x_);
    HYPRE_ClearAllErrors();
    check(HYPRE_StructVectorGetBoxValues(x_, lo_, hi_, z), "StructVectorGetBoxValues");
  }

 private:
  MPI_Comm comm_;
  HYPRE_Int lo_[3], hi_[3];
  HYPRE_StructGrid grid_ = nullptr;
  HYPRE_StructStencil stencil_ = nullptr;
  HYPRE_StructMatrix A_ = nullptr;
  HYPRE_StructVector b_ = nullptr, x_ = nullptr;
  HYPRE_StructSolver solver_ = nullptr;
  long n_ = 0;
  std::vector<double> buf_;
};

}  // namespace

bool have_pfmg() { return true; }
std::unique_ptr<DistPreconditioner> make_pfmg_preconditioner(const DistPoisson& op) {
  return std::make_unique<Pfmg>(op);
}

#endif

}  // namespace cgdem::air_mpi
