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
// Porosity next to walls (porosity.cpp; docs/coupling.md): with masked weights a cell that
// a wall cuts receives less of a neighbouring parcel's volume than its share of the space
// the parcel fills, and no parcel centre comes closer to a wall than its radius r, so
// 1 - V_s/dx^3 of a cut cell (walls counted as void) reads 0.7-0.99 in powder packed at
// 0.4, and the air found the powder next to every moving wall ~20-1000 times too
// permeable. With WallPorosity::Packing the porosity is that of the packing:
//   eps(c) = max(eps_min, 1 - V_s(c)/(C(c) dx^3)),  C(c) = (1/dx^3) Int_{phi >= r} w~_c(x) dx,
// (V_s/(C dx^3) bounded by packing_max unless V_s/dx^3 itself exceeds it),
// the kernel capacity of the cell for parcel centres (what a packing of solid fraction 1
// filling every reachable place deposits there; 1 away from walls, so nothing changes
// there). The whole cell's non-solid fraction mix = 1 - V_s/dx^3 is kept for the air's
// continuity (porosity_source) and the drag deposits are divided by the face mean of C
// (the drag per volume the packing fills).
// Weights: every transfer of a step reads the same kernel weights of a parcel (its cell
// stencil and its three face stencils, masked by the same walls), so they are built once
// per position (ParcelWeights, in parallel) and handed to the transfers. Deposits run
// serially in particle order (deterministic); gathers run in parallel.
#pragma once
#include <array>
#include <vector>

#include "coupling/drag.hpp"
#include "coupling/kernel.hpp"
#include "fluid/field_sync.hpp"
#include "fluid/fluid_state.hpp"
#include "fluid/ibm.hpp"
#include "particles/particles.hpp"
#include "particles/species.hpp"

namespace cgdem::coupling {

// How the porosity of a cell that walls cut (or that lies within a parcel radius of a wall)
// is taken ("Porosity next to walls" below).
enum class WallPorosity {
  Packing,  // eps = 1 - V_s/(C dx^3): the porosity of the packing the parcels form (default)
  Cell,     // eps = 1 - V_s/dx^3: the part of the whole cell not filled by solid, walls counted as void
};

struct ExchangeParams {
  DragLaw law = DragLaw::ErgunWenYu;
  AirProperties air;
  double eps_min = 0.2;                         // lower bound of the mapped void fraction
  fluid::FluidBoundary bc{};                    // of the air (periodic axes, pressure ghosts)
  WallPorosity wall_porosity = WallPorosity::Packing;  // cells next to walls (below)
  double packing_max = 0.64;  // bound of the normalized solid fraction V_s/(C dx^3): random
                              // close packing of equal spheres (Scott & Kilgour 1969: 0.637)
};

struct VoidStats {
  long normalized_cells = 0;  // cells whose porosity was normalized by a capacity C < 1
  double parcel_volume = 0;   // sum of V_p of the parcels mapped [m^3]
  double grid_volume = 0;     // sum over cells of V_s before clipping [m^3]
  long clipped_cells = 0;     // cells where 1 - V_s/dx^3 < eps_min
  double eps_min_raw = 1;     // smallest 1 - V_s/dx^3 before clipping
  std::array<long, 2> capacity_nodes{};  // kernel capacities of the nodes near walls holding
                                         // solid, summed over the radii: from the cache, evaluated
};

// What step 3 gives besides the porosity eps (exchange.hpp, "Porosity next to walls").
struct VoidFields {
  fluid::Field mix;  // max(eps_min, 1 - V_s/dx^3): the non-solid part of the whole cell (walls
                     // count as void); its change over a step is what the parcels' motion
                     // displaces (sum over cells of V_s is the parcels' volume)
  fluid::Field cap;  // kernel capacity C of each cell for the parcels' centres (1 away from walls)
  bool normalized = false;  // some cell has C < 1 (eps differs from mix there)
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
  // The same, and the mixture fraction and capacities (walls and scene frame as set).
  VoidStats void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps, VoidFields& vf) const;
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

  // The air's continuity with the porosity of the packing next to walls: the cell source
  //   m = [(mix^{n+1} - mix^n) - (eps^{n+1} - eps^n)]/dt_f + div((mix_f - E_f) U_B,f)
  // [1/s] that turns the air solver's d(eps)/dt + div(E u) into
  //   d(mix)/dt + div(E u + (mix_f - E_f) U_B) = 0,
  // the balance of the non-solid volume of the cells when E is the packing's porosity (face
  // means) and u the volume-weighted velocity of air and wall (eq. 18): mix - eps is the
  // walls' share of a cell's non-solid volume, and it moves with the nearest wall (U_B, its
  // velocity). Where everything translates with a wall the flux is mix U_B, as it is with
  // eps = mix; next to static walls it is E u. mass is left empty when no cell is normalized.
  void porosity_source(const VoidFields& now, const fluid::Field& mix_old, const fluid::Field& eps_new,
                       const fluid::Field& eps_old, double dt_f, fluid::Field& mass) const;
  // Capacities used by the drag deposits (K, Kv divided by the face mean of C, the drag per
  // volume the parcels can fill; null or not normalized: undivided). Must stay valid.
  void set_void_fields(const VoidFields* vf) { void_fields_ = vf; }
  // The walls' positions for the capacities (phi of eq. 15; null: no walls). Must stay valid.
  void set_frame(const geometry::Scene::Frame* frame) { frame_ = frame; }
  // Kernel capacity C_r of the cells for parcel centres of radius r (porosity.cpp): 1 except
  // at the nodes holding solid (solid > 0) near walls or the domain's ends. Returns how
  // many of the nodes it needed it took from its cache of the static walls' values
  // (porosity.cpp) and how many it evaluated.
  std::array<long, 2> capacity(double r, const fluid::Field& solid, fluid::Field& cap) const;

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
  // Face gradients of the pressure (domain ghosts from the boundary conditions), into
  // grad_scratch_ (valid until the next call).
  const std::array<fluid::Field, 3>& pressure_gradient(const fluid::FluidState& air) const;
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
  VoidStats void_fraction(const Particles& p, const ParcelWeights& w, fluid::Field& eps, VoidFields& vf,
                          bool packing) const;
  // vs: all the parcels' solid, vs_r: that of each radius (empty when there is one radius).
  void porosity_of_packing(fluid::Field& vs, std::vector<fluid::Field>& vs_r, VoidFields& vf, fluid::Field& eps,
                           VoidStats& st) const;
  // Capacity quadrature of one cell (porosity.cpp).
  std::vector<unsigned char> near_walls(int reach) const;
  bool plain_cell(int i, int j, int k, const std::vector<unsigned char>& near) const;
  // A cell with no wall near adds the tabulated shares to cap; one near a wall gives its
  // sub-cubes' deposits (at most 27, in the order they are added) to `out`.
  struct CapacityItem {
    Weights w;
    double v;
  };
  void deposit_plain_capacity(int i, int j, int k, fluid::Field& cap) const;
  int cell_capacity_items(int i, int j, int k, double r, CapacityItem* out) const;
  void add_cell_capacities(const std::vector<std::array<int, 3>>& cells, double r,
                           const std::vector<unsigned char>& near, fluid::Field& raw) const;
  bool reachable_part(const Vec3& c, double h, double r, double& frac, Vec3& centroid) const;
  // Face mean of the capacity C on face (i, j, k) of axis d (1 where not normalized).
  double face_capacity(int d, int i, int j, int k) const;
  // Capacities that no moving part can reach (porosity.cpp, capacity()): a node whose
  // surroundings are farther than the margin from every moving part's bounds has the
  // capacity of the static walls alone, computed once and kept. One per parcel radius;
  // emptied when the scene, the wall fractions or a static body's offset change.
  struct CapacityCache {
    const geometry::Scene* scene = nullptr;
    const fluid::IbmFractions* walls = nullptr;
    std::vector<Vec3> offsets;           // the bodies' offsets when filled (static ones compared)
    fluid::Field value;                  // the capacity, where known or recent
    std::vector<unsigned char> known;    // per cell of the block (index i + nx (j + ny k)): the
                                         // static walls' value, for any place of the moving ones
    // The value at the placement `recent_offsets` of every body (moving ones included): the
    // nodes a moving part reaches, kept for the next call while nothing moves (a shoe at rest).
    std::vector<Vec3> recent_offsets;
    std::vector<unsigned char> recent;
  };
  // The cache of radius r, emptied if stale; null when none applies (over MPI ranks, no
  // walls, or r not a parcel radius of the species).
  CapacityCache* capacity_cache(double r) const;
  mutable std::vector<CapacityCache> capacity_cache_;  // per entry of radii_
  // Working arrays of void_fraction() and capacity(), kept from call to call so that none is
  // allocated and value-initialized per call (the items alone are 12 MB on the die grid);
  // each is rewritten before it is read.
  struct VoidScratch {
    fluid::Field vs;               // the parcels' solid volume per cell
    std::vector<fluid::Field> cap; // the capacity of each parcel radius
    std::vector<unsigned char> need, dep;  // per padded cell index (cell_layout_)
    std::vector<unsigned char> keep;       // per own cell (capacity())
    fluid::Field raw;
    std::vector<std::array<int, 3>> cells;
    std::vector<CapacityItem> items;
    std::vector<int> count;
  };
  mutable VoidScratch scratch_;
  // The pressure with its ghosts and its face gradients (pressure_gradient()), kept from
  // call to call for the same reason: twice per fluid step, four fields of the grid's size.
  struct GradScratch {
    fluid::Field p;
    std::array<fluid::Field, 3> grad;
  };
  mutable GradScratch grad_scratch_;
  const fluid::IbmFractions* walls_ = nullptr;
  const geometry::Scene::Frame* frame_ = nullptr;
  const VoidFields* void_fields_ = nullptr;
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
  std::vector<int> radius_group_;             // per species: index into radii_
  std::vector<double> radii_;                 // the distinct parcel radii [m]
  Lattice cells_;
  std::array<Lattice, 3> faces_;
};

}  // namespace cgdem::coupling
