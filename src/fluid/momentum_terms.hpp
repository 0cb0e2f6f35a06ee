// Explicit momentum terms of the volume-averaged air equation (paper eqs. 13, 19) on the MAC
// grid, for one velocity component d at its faces. Both ADD their contribution to `rhs`
// (units N/m^3 = kg m^-2 s^-2), over the faces [lo, hi) given per axis.
//
// Advection, conservative form  -div(eps rho u u_d):
//   for each direction e the flux through the upper e-side of the control volume of face
//   idx is F_e(idx) = M_e(idx) q_e(idx), with the mass flux built from the SAME face fluxes
//   eps_f u_f that enter continuity (so a uniform u_d is preserved exactly, eq. 12):
//     M_e(idx) = rho/2 [ (eps u_e)(idx + e) + (eps u_e)(idx - d + e) ]
//   and q_e the advected value reconstructed from the upwind side of M:
//     q = u_c + 1/2 psi(a, b),  a = u_c - u_far,  b = u_down - u_c
//   with the limiter psi: upwind 0; central b; van Leer 2ab/(a+b) (ab > 0, else 0);
//   MC sign(b) min(2|a|, |a+b|/2, 2|b|) (ab > 0, else 0). The TVD limiters keep the
//   reconstruction bounded at any cell Reynolds number.
//   rhs(idx) -= sum_e [F_e(idx) - F_e(idx - e)] / dx
//
// Viscous stress, div(eps tau) with tau = mu (grad u + grad u^T) - 2/3 mu (div u) I:
//   T_d(c)     = eps_c mu [ 2 (u_d(c+d) - u_d(c))/dx - 2/3 div u(c) ]        at cell centres
//   T_e(edge)  = eps_edge mu [ (u_d(idx+e) - u_d(idx))/dx + (u_e(idx+e) - u_e(idx-d+e))/dx ]
//   eps_edge the mean of the four cells around the edge,
//   rhs(idx) += sum_e [T_e(idx) - T_e(idx - e)] / dx
//
// Reads: velocities and eps with valid ghost layers (boundary.hpp). Writes: rhs only.
//
// Implementation: one fused sweep per component (add_momentum_terms). Every flux/stress is
// evaluated once: per row (j, k), the upper-side fluxes in x, y and z are computed into row
// buffers by plain loops over i without branches (both upwind reconstructions computed and
// one selected, the limiters written as selects, the scheme, the component, the direction
// and the advect/viscous switches template arguments), which the compiler vectorizes; a last
// loop over the row forms the divergence from them and from the buffers of the row below (y)
// and of the plane below (z). The arithmetic of each face is exactly that of the formulas
// above (bitwise the same as evaluating each side separately). The planes are compiled for
// the baseline target, AVX2 and AVX-512 (the best one available runs), all without
// floating-point contraction, so all three give the same bits. OpenMP splits the k range
// into contiguous chunks (of equal work when spans are given); each chunk evaluates the
// z-fluxes of the plane below it, so the result does not depend on the number of threads.
#pragma once
#include <array>
#include <string>

#include "fluid/mac_grid.hpp"

namespace cgdem::fluid {

enum class Advection { Upwind, Central, VanLeer, MC };

Advection advection_from_string(const std::string& name);  // "upwind", "central", "van-leer", "mc"

using FaceRange = std::array<std::array<int, 2>, 3>;  // [lo, hi) per axis

// vel[e] = velocity component e; eps_face[e] = eps on the e-faces.
void add_advection(const MacGrid& g, int d, Advection scheme, double rho, const std::array<const Field*, 3>& vel,
                   const std::array<const Field*, 3>& eps_face, const FaceRange& range, Field& rhs);

void add_viscous(const MacGrid& g, int d, double mu, const std::array<const Field*, 3>& vel, const Field& eps_cell,
                 const FaceRange& range, Field& rhs);

// The faces of each row (j, k) of a range to evaluate: lo[q] <= i < hi[q], with q = (j - lo_j) +
// n_j (k - lo_k) and range[0][0] <= lo[q] <= hi[q] <= range[0][1] (lo = hi: none).
// work[m] (m = 0 .. n_k): the cost of the first m planes, by which the planes are shared
// between threads (plane_chunk): per row, the faces in its span, those outside it divided by
// kCopyShare (the predictor copies U_B there) and kRowWork.
struct RowSpans {
  const int *lo, *hi;
  const long* work;
};
inline constexpr long kRowWork = 8, kCopyShare = 4;

// The faces [first, second) of row (j, k) of range r to evaluate: its span, or the whole row
// without spans.
inline std::array<int, 2> row_span(const RowSpans* spans, const FaceRange& r, long j, long k) {
  if (!spans) return r[0];
  const long q = (j - r[1][0]) + (r[1][1] - r[1][0]) * (k - r[2][0]);
  return {spans->lo[q], spans->hi[q]};
}

// Planes [first, second) of thread t of nth over the n_k planes from k0: contiguous chunks of
// about equal work (spans->work), or of equal plane counts without spans.
std::array<int, 2> plane_chunk(const RowSpans* spans, int k0, int nk, int t, int nth);

// Both terms in one sweep: rhs = (rhs - [advection divergence]/dx) + [viscous divergence]/dx,
// the same operations in the same order as add_advection followed by add_viscous.
// `advect` / mu > 0 switch the two parts.
// spans (optional): only those faces of each row are written; the others keep their value.
// The fluxes a written face needs are evaluated whatever the spans, so the written faces get
// the same bits as without spans.
void add_momentum_terms(const MacGrid& g, int d, bool advect, Advection scheme, double rho, double mu,
                        const std::array<const Field*, 3>& vel, const std::array<const Field*, 3>& eps_face,
                        const Field& eps_cell, const FaceRange& range, Field& rhs,
                        const RowSpans* spans = nullptr);

}  // namespace cgdem::fluid
