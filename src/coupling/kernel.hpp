// Particle <-> grid transfer kernel of the coupling: the quadratic B-spline ("triangular
// shaped cloud", TSC), the same for every quantity so that mapping and interpolation are
// adjoint (what a parcel deposits at a node is what it reads back from that node).
//
// A lattice is a set of nodes  x_n = origin + (i, j, k) h,  0 <= i < n[0] etc.: the cell
// centres of the MAC grid, or the faces of one velocity component. For a point x the
// kernel has 3 nodes per axis; with s = (x_a - origin_a)/h, i0 = round(s), t = s - i0:
//     w(i0-1) = (1/2 - t)^2 / 2,   w(i0) = 3/4 - t^2,   w(i0+1) = (1/2 + t)^2 / 2,
// a partition of unity (sum 1), C1 in x, support 3h. Nodes outside the lattice are folded
// back: wrapped on periodic axes, clamped to the nearest boundary node otherwise. Weights
// are never dropped, so every deposit conserves its total exactly (to round-off).
//   reads  nothing global; pure functions of the lattice and the point.
#pragma once
#include <array>

#include "core/vec3.hpp"
#include "fluid/mac_grid.hpp"

namespace cgdem::coupling {

struct Lattice {
  Vec3 origin{};              // node (0,0,0) [m]
  double h = 1;               // node spacing [m]
  std::array<int, 3> n{};     // nodes per axis
  std::array<bool, 3> periodic{false, false, false};
  // On a block of a grid over MPI ranks: beyond side 2 a + h lie the ghost layers of a
  // neighbouring block. Nodes there are kept, not folded back (up to kGhost of them; the
  // deposit is then summed into the block that owns them, fluid/field_sync.hpp).
  std::array<bool, 6> ghost_side{};
};

// Cell centres of the grid.
Lattice cell_lattice(const fluid::MacGrid& g, std::array<bool, 3> periodic);
// Faces of velocity component d. On a periodic axis d the face n is the image of face 0
// and is not a node (copy it after depositing: sync_periodic_face).
Lattice face_lattice(const fluid::MacGrid& g, int d, std::array<bool, 3> periodic);

// The 27 nodes and weights of one point: node (idx[0][a], idx[1][b], idx[2][c]) has
// weight w[0][a] w[1][b] w[2][c].
struct Stencil {
  std::array<std::array<int, 3>, 3> idx;
  std::array<std::array<double, 3>, 3> w;
};

Stencil tsc_stencil(const Lattice& L, const Vec3& x);

// The same 27 nodes as flat indices into fields of the lattice's layout, with weights that
// may be reshaped node by node. Walls: masked(s, alpha) multiplies each node's weight by
// (1 - alpha(node)) and rescales the sum back to 1, so that a parcel next to a wall puts
// nothing into (and reads nothing from) nodes inside the wall, and deposits still conserve
// exactly. A parcel whose 27 nodes are all inside walls keeps the plain weights.
struct Weights {
  std::array<long, 27> idx;
  std::array<double, 27> w;
};
Weights flatten(const Stencil& s, const fluid::Field& layout);
// `layout` gives the index layout (any field of the lattice); alpha may be empty (no walls).
Weights masked(const Stencil& s, const fluid::Field& alpha, const fluid::Field& layout);
// Two masks at once: weight x (1 - alpha) x (1 - blocked), e.g. wall fractions and the
// prescribed faces on the domain's wall sides.
Weights masked(const Stencil& s, const fluid::Field& alpha, const fluid::Field& blocked, const fluid::Field& layout);

// f(node) += value * weight(node) for the 27 nodes.
void deposit(const Weights& s, double value, fluid::Field& f);
// sum over the 27 nodes of weight(node) f(node).
double interpolate(const Weights& s, const fluid::Field& f);

// A d-face field read with the weights a cell-centred deposit gives the faces when face
// values are the mean of their two cells (face i between cells i-1 and i):
//   sum_cells w_c (f(face c) + f(face c+1)) / 2.
// Used for the pressure-gradient force so that the parcels feel exactly the (1 - E) grad p
// that the air's eps-weighted pressure term leaves out (E = face mean of eps).
double interpolate_cell_faces(const Weights& cell_weights, const fluid::Field& cell_layout, int d,
                              const fluid::Field& f);
// Face field of component d on a periodic axis d: face n := face 0.
void sync_periodic_face(int d, std::array<bool, 3> periodic, fluid::Field& f);

}  // namespace cgdem::coupling
