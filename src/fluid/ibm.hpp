// Immersed-boundary volume fractions of the air grid (paper eqs. 18-20).
//
// alpha is the fraction of a control volume inside the walls, computed from the SAME signed
// distance as the particle contacts (Scene::Frame::solid_fraction, n^3 midpoint samples):
//   cells:   the cell [x_c - dx/2, x_c + dx/2]^3,
//   d-faces: the face control volume, a cube of edge dx centred on the face (it spans the
//            halves of the two cells the face separates).
// U_B on a face is the velocity of the body nearest to the face centre (eq. 18); it is set
// only where alpha > 0 (zero elsewhere).
//
// Cost: solid_fraction returns after one phi evaluation when the box is farther than its
// half-diagonal from every surface, so only the faces near a surface are sub-sampled.
// The fractions are recomputed only when a body has moved since the last call.
#pragma once
#include <array>
#include <vector>

#include "fluid/mac_grid.hpp"
#include "geometry/scene.hpp"

namespace cgdem::fluid {

struct IbmFractions {
  std::array<Field, 3> alpha_face;  // wall fraction on the d-faces, in [0, 1]
  std::array<Field, 3> ub_face;     // U_B,d on the d-faces [m/s]
  Field alpha_cell;                 // wall fraction of the cells
  bool any_solid = false;           // some alpha > 0
  long sampled_faces = 0;           // faces that needed sub-sampling in the last update

  // Cached body offsets of the last computation (recompute when they change).
  std::vector<Vec3> offsets;
  bool valid = false;
};

// Recomputes the fractions for `frame` if the bodies have moved (or on first use).
// Returns true when they were recomputed. `samples` = n of the n^3 sub-samples (>= 1).
bool update_ibm(const MacGrid& g, const geometry::Scene::Frame& frame, int samples, IbmFractions& ibm);

}  // namespace cgdem::fluid
