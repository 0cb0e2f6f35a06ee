// Single-precision copy of a Poisson7 operator, for the multigrid preconditioner's smoother,
// residual and transfers (mixed precision: PCG runs in double, the V-cycle in float).
//
// Scaling: the copy holds s w_f and s D_c with s = 2^-e, 2^e the power of two nearest to the
// largest diagonal of the finest level, the same s on every level. The V-cycle built from these
// operators approximates (s A)^{-1} = A^{-1}/s, so the caller multiplies its output by s. A power
// of two keeps the scaling exact; it only keeps the float values near 1 whatever the units.
//
// Why float is enough: the preconditioner only has to be a fixed, nearly symmetric positive
// operator; its rounding (relative 6e-8) perturbs M^{-1}, not the residual PCG computes in
// double, so the final accuracy is that of the double PCG (tests/pressure/test_methods.cpp).
//
// Red-black Gauss-Seidel, the same sweep order (and the same thread-independent plane chunking
// of the fused pair) as Poisson7::gauss_seidel_pair, see poisson7.hpp:
//   x_c = (b_c + sum_nb w_f x_nb) * (1/D_c)
// or over-relaxed (omega != 1, set()): x_c = (1 - omega) x_c + (b_c + sum_nb w_f x_nb) * (omega/D_c).
// A cell with D_c = 0 (all faces blocked) gets x_c = 0, where the double smoother leaves it
// alone: such a cell, and the fine cells under a coarse one, form floating components that
// the Krylov solver projects to mean zero after the preconditioner, so z is the same; the
// branch-free update vectorises.
// Restriction of the residual R (b - A x), R = P^T/8 (2x2x2 children; fewer at an odd edge),
// is computed row by row without storing b - A x.
//
// Skipping blocked cells (set(..., active)): every loop visits only the segments of `active`
// (active_rows.hpp), which must hold every cell with D > 0. A cell left out has D = 0 and no
// open face, so what it holds reaches its neighbours only through weights of 0. It must also
// have b = 0: on the finest level b is the PCG residual, which is 0 there (the right-hand side
// is projected, and (A x)_c = 0); on a coarse level the multigrid leaves out only cells whose
// fine cells were all left out (their restricted residual is then 0; a coarse cell without
// open coarse faces can still cover fine cells connected inside it, and those it keeps).
// Skipping such a cell leaves x there unwritten and drops its residual, 0, from the
// restriction: the other cells get the same values (up to the sign of a zero). Nothing may
// read x there (the prolongation below only reads the parents of visited cells; the
// multigrid writes z = 0 there).
#pragma once
#include <vector>

#include "solvers/pressure/poisson7.hpp"

namespace cgdem::pressure {

class Stencil32 {
 public:
  // Copies op's weights and diagonal times `scale` in single precision; omega: the relaxation
  // factor of the smoother (1: plain Gauss-Seidel).
  // active: the segments the loops visit (above; copied), nullptr: every cell.
  void set(const Poisson7& op, double scale, double omega = 1.0, const ActiveRows* active = nullptr);

  // Two half-sweeps, colour `first` then 1 - first. zero_start: x is taken as 0 on entry and
  // need not be initialised (the first colour is then b_c / D_c).
  void gs_pair(const float* b, float* x, int first, bool zero_start) const;
  // bc = R (b - A x) on the coarse grid `c` (n_c = ceil(n/2) per axis).
  void restrict_residual(const float* b, const float* x, const GridSpec& c, float* bc) const;
  // x += P xc: piecewise-constant prolongation from the coarse grid `c`.
  void prolong_add(const GridSpec& c, const float* xc, float* x) const;

  long n() const { return g_.cells(); }
  const GridSpec& grid() const { return g_; }
  // The rows' segments the loops visit (all cells unless set() was given some).
  const ActiveRows& active() const { return act_; }

 private:
  // kNormal: the update above; kFromZero: the same with x_c = 0 before it (the second colour of
  // a pair that starts from x = 0, whose x_c is not initialised); kZeroFirst: the first colour of
  // that pair (x = 0 around it: x_c = b_c omega/D_c).
  enum class Mode { kNormal, kFromZero, kZeroFirst };
  void gs_row(const float* b, float* x, int j, int k, int color, Mode mode) const;
  void gs_color(const float* b, float* x, int color, Mode mode) const;
  void residual_row(const float* b, const float* x, int j, int k, int lo, int hi, float* r) const;

  GridSpec g_;
  bool px_ = false, py_ = false, pz_ = false;
  std::vector<float> wx_, wy_, wz_, d_, id_;  // id_ = omega/D (0 where D = 0)
  float keep_ = 0;                            // 1 - omega
  ActiveRows act_;
};

// Power of two nearest to 1 / max(D) of op (1 if D = 0 everywhere).
double stencil32_scale(const Poisson7& op);

}  // namespace cgdem::pressure
