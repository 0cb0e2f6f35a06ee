// Particle <-> air exchange of the coupled method (paper eqs. 8-11, 14), all through the
// one TSC kernel of kernel.hpp:
//
//   void fraction   V_s(c) = sum_p w_c(x_p) V_p,   eps(c) = max(eps_min, 1 - V_s(c)/dx^3)
//                   (sum_c V_s(c) = sum_p V_p exactly; cells clipped at eps_min are counted)
//   air at parcel   u_f(x_p) = sum_f w_f(x_p) u(f) per component on its face lattice,
//                   eps(x_p) likewise from the cells, grad p(x_p) from the face gradients
//                   (p(c) - p(c-1))/dx read through the parcel's CELL weights (each cell
//                   passes half its weight to each of its two d-faces): the parcels then
//                   feel exactly the sum_f (1 - E_f) grad p_f dx^3 that the air's E grad p
//                   leaves out (E_f = face mean of eps, as the air solver uses it)
//   parcel forces   drag   c_p = V_p beta/(1-eps)(eps(x_p), |u_f - v_p|, d_O)   eq. (8)
//                   F_D = c_p (u_f - v_p)   (integrated implicitly by DemSolver::kick)
//                   f_ext = -V_p grad p(x_p)
//   air reaction    K(f)  = sum_p w_f(x_p) c_p / dx^3,   Kv(f) = sum_p w_f(x_p) c_p vbar_p / dx^3
//                   so that the air feels -f = K (vbar - u) per volume (eq. 14, implicit in
//                   u); c_p vbar_p = c_p u_f - J_p/dt_f with J_p the drag impulse the parcel
//                   received over the step (Particles::j_drag): vbar is the drag-weighted
//                   mean parcel velocity, so the air gets exactly -J_p when u stays u_f.
//   end-of-step     the parcels then receive the difference between the drag at the end of
//   correction      the step and the drag they were given, as the backward-Euler response
//                   of the parcel to the change of the air velocity (a = dt_f c_p):
//                   dv_p = a/(m_p + a) (u^{n+1}(x_p) - u_f)
//                   For a << m_p this is dt_f c_p (u^{n+1} - u_f) / m_p, which makes the
//                   drag exchange momentum-conserving (deposit and interpolation use the
//                   same weights: sum_f w_f K u = sum_p c_p u(x_p)), i.e. implicit in both
//                   phases. In a packed bed a/m_p reaches ~270 at the largest fluid step:
//                   the plain kick multiplied every change of u by that factor and shook a
//                   bed at rest; this one is bounded by the change itself, at the price of
//                   a momentum error a^2/(m_p + a) (u^{n+1} - u_f), first order in dt_f and
//                   only where the drag is stiff. The pressure force is NOT corrected the
//                   same way: applied as a kick, the change of grad p over a step drives a
//                   period-2 instability of a free packed bed at fluid steps >= 1e-3 s (the
//                   d(eps)/dt source makes p stiff in the parcel positions); it lags by one
//                   fluid step instead, a momentum error of first order in dt_f.
//
// Walls: every weight is multiplied by (1 - alpha) of its node (cell or face) and the
// weights are rescaled to sum 1 (kernel.hpp, masked): parcels next to the die floor put
// their volume into the air cells above it, not into the floor, and drag is exchanged only
// with faces where the air moves. The boundary faces of the domain's wall sides are
// masked the same way (prescribed velocity: a deposit there would be lost to the wall).
// Conservation and adjointness hold as before.
// Weights: every transfer of a step reads the same kernel weights of a parcel (its cell
// stencil and its three face stencils, masked by the same walls), so they are built once
// per position (ParcelWeights, in parallel) and handed to the transfers. Deposits run
// serially in particle order (deterministic); gathers run in parallel.
#pragma once
#include <vector>

#include "coupling/drag.hpp"
#include "coupling/kernel.hpp"
#include "fluid/field_sync.hpp"
#include "fluid/fluid_state.hpp"
#include "fluid/ibm.hpp"
#include "particles/particles.hpp"
#include "particles/species.hpp"

namespace cgdem::coupling {

struct ExchangeParams {
  DragLaw law = DragLaw::ErgunWenYu;
  AirProperties air;
  double eps_min = 0.2;                         // lower bound of the mapped void fraction
  fluid::FluidBoundary bc{};                    // of the air (periodic axes, pressure ghosts)
};

struct VoidStats {
  double parcel_volume = 0;   // sum of V_p of the parcels mapped [m^3]
  double grid_volume = 0;     // sum over cells of V_s before clipping [m^3]
  long clipped_cells = 0;     // cells where 1 - V_s/dx^3 < eps_min
  double eps_min_raw = 1;     // smallest 1 - V_s/dx^3 before clipping
};

// The masked kernel weights of every parcel at one set of positions and wall fractions.
// Index i is parcel i of the Particles they were built from; valid until the parcels move,
// are re-sorted or the walls change.
struct ParcelWeights {
  std::vector<Weights> cell;
  std::array<std::vector<Weights>, 3> face;
  size_t size() const { return cell.size(); }
};

class Exchange {
 public:
  Exchange(const fluid::MacGrid& g, const std::vector<Species>& species, ExchangeParams params);

  // The weights of every parcel at its current position with the current walls (parallel).
  void weights(const Particles& p, ParcelWeights& w) const { weights(p, p.size(), w); }
  // Of parcels 0 .. n-1 only (over MPI ranks: the owned ones, not the ghosts).
  void weights(const Particles& p, size_t n, ParcelWeights& w) const;

  // Every transfer takes the weights of the parcels' current positions and acts on the
  // parcels 0 .. w.size()-1 (precondition: built by weights() after the parcels last moved).
  // eps from the parcel positions (writes every interior cell of eps).
  VoidStats void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps) const;
  VoidStats void_fraction(const Particles& p, fluid::Field& eps) const;  // builds the weights
  // Sets p.u_fluid, p.drag and p.f_ext from the air state (u, p, eps of `air`).
  void air_to_parcels(const fluid::FluidState& air, const ParcelWeights& w, Particles& p) const;
  // K and Kv of src (resized to the face layout) from p.drag, p.u_fluid and p.j_drag
  // accumulated over a fluid step of dt_f.
  void parcels_to_air(const Particles& p, const ParcelWeights& w, double dt_f, fluid::Sources& src) const;
  // End-of-step drag correction of the parcel velocities (and their fluid work) from the air
  // velocity at t^{n+1} (bounded kick, see above); reads p.drag, p.u_fluid as set by
  // air_to_parcels at t^n.
  void correct_parcels(const fluid::FluidState& air, const ParcelWeights& w, double dt_f, Particles& p) const;

  // The implicit coupling (solvers/coupled/implicit_drag.hpp), after the DEM substeps of a step:
  // the drag-weighted mean velocity of every parcel over the step, vbar_p = u_f - J_p/(dt_f c_p)
  // (the velocity the semi-implicit deposit uses implicitly; v_p itself for a parcel held in place).
  void mean_parcel_velocities(const Particles& p, size_t n, double dt_f, std::vector<Vec3>& vbar) const;
  // c_p = V_p beta/(1-eps) at the parcel from the air velocity and eps of `air` (u^{n+1} and
  // eps^{n+1} in the implicit step), with the slip |u(x_p) - vbar_p| (eqs. 8-11).
  void drag_at(const fluid::FluidState& air, const ParcelWeights& w, const Particles& p,
               const std::vector<Vec3>& vbar, std::vector<double>& c) const;
  // K = sum_p w_f c_p / dx^3 and Kv = sum_p w_f c_p vbar_p / dx^3 (the air then feels
  // c_p (vbar_p - u) per parcel, implicit in u).
  void deposit_drag(const ParcelWeights& w, const std::vector<double>& c, const std::vector<Vec3>& vbar,
                    fluid::Sources& src) const;
  // End-of-step correction of the implicit step: the parcel receives what the air lost,
  // dt_f c_p (u^{n+1}(x_p) - vbar_p), less the impulse J_p it was given over the substeps,
  // bounded by the same backward-Euler factor 1/(1 + a/m_p), a = dt_f c_p. With c_p equal to
  // the coefficient of the substeps this is correct_parcels' kick.
  void correct_parcels_implicit(const fluid::FluidState& air, const ParcelWeights& w, double dt_f,
                                const std::vector<double>& c, const std::vector<Vec3>& vbar, Particles& p) const;

  // Wall fractions used to mask the weights (null: no walls). The pointer must stay valid.
  // Over MPI ranks their ghost layers on the cut sides must hold the neighbours' values.
  void set_walls(const fluid::IbmFractions* walls) { walls_ = walls; }
  // On a block of a grid over MPI ranks (fluid/field_sync.hpp; the grid and params.bc are
  // the block's): the kernels reach into the ghost layers on the cut sides, deposits are
  // summed over the blocks, the void fraction's and pressure's ghosts come from the
  // neighbours. Without it (the default) the exchange is the serial one. VoidStats then
  // hold this block's part (the caller sums them). The sync must outlive the exchange.
  void set_sync(fluid::FieldSync* sync);

  const ExchangeParams& params() const { return params_; }
  const std::array<bool, 3>& periodic() const { return periodic_; }

 private:
  struct AirSample {
    double eps;
    Vec3 u, grad_p;
  };
  // Face gradients of the pressure (domain ghosts from the boundary conditions).
  std::array<fluid::Field, 3> pressure_gradient(const fluid::FluidState& air) const;
  AirSample sample(const fluid::FluidState& air, const std::array<fluid::Field, 3>& grad, const ParcelWeights& w,
                   size_t i) const;
  // K, Kv of src from coef(i) = (c_i/dx^3, c_i vbar_i/dx^3) per parcel: deposited serially in
  // parcel order, then periodic images folded and the blocks over ranks summed.
  template <class Coefficients>
  void deposit_sources(const ParcelWeights& w, fluid::Sources& src, Coefficients coef) const;
  // Adds impulse(i, u^{n+1}(x_i)) to every parcel's velocity, drag impulse and fluid work.
  template <class Impulse>
  void kick_parcels(const fluid::FluidState& air, const ParcelWeights& w, Particles& p, Impulse impulse) const;
  Weights cell_weights(const Vec3& x, const fluid::Field& layout) const;
  Weights face_weights(int d, const Vec3& x, const fluid::Field& layout) const;
  const fluid::IbmFractions* walls_ = nullptr;
  fluid::FieldSync* sync_ = nullptr;
  fluid::Field no_alpha_;
  // 1 on the boundary faces of the domain's Wall sides (their velocity is prescribed, so
  // drag deposited there would never reach the air), 0 elsewhere.
  std::array<fluid::Field, 3> blocked_;
  fluid::Field cell_layout_;  // the index layout of cell fields (the face layouts: blocked_)

  fluid::MacGrid g_;
  ExchangeParams params_;
  std::array<bool, 3> periodic_{};
  std::vector<double> volume_, d_original_;  // per species
  Lattice cells_;
  std::array<Lattice, 3> faces_;
};

}  // namespace cgdem::coupling
