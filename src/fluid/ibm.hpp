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
// Cost: only boxes within their half-diagonal of a surface are sub-sampled. The fractions
// are recomputed only when a body has moved since the last call, and then only near the
// moving bodies: the fractions, phi and nearest part of the STATIC bodies alone are cached
// (recomputed when a static body's offset, the grid or `samples` change), and a box is
// re-evaluated only inside the union of the moving parts' bounds at this and the previous
// call, widened by a box half-diagonal plus one cell. There a box takes the static value
// when no moving part's bounds come within its half-diagonal; otherwise its samples are
// tested against the parts whose bounds contain them. This is the same count of samples
// inside the walls as testing every part at every sample (phi < 0 exactly inside a part, and
// a part's bounds contain it), so alpha is identical to a full recomputation; U_B is that of
// the nearest part as before (identical when the parts' signed distances are exact, e.g.
// boxes).
// Inside the region, a box need not be evaluated while the moving bodies have travelled
// less than its clearance since it was. A signed distance changes by at most the distance
// a body moves (shape.hpp: |s| is the distance to the surface or a lower bound of it, so s
// is 1-Lipschitz), so a box whose centre was phi_m >= h_d + c from the moving parts within
// reach (h_d its half-diagonal), and whose other moving parts' bounds were farther than
// h_d + c, keeps both until they have travelled c: no sample of it can be in a moving part,
// no moving part is nearer than a static one where it has solid, and its value is the
// static one. A box whose centre was phi_m <= -h_d - c
// inside the one moving body, and nearer to it than to any static part by more than c,
// stays alpha = 1 with that body's velocity. The travel is summed over the calls (the
// largest displacement of a moving body at each), so motion back and forth is covered.
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

  // Static bodies alone, per box array (0: cells, 1 + d: d-faces): fraction, phi at the box
  // centre, nearest static part (-1: none) and its velocity component.
  struct StaticCache {
    const geometry::Scene* scene = nullptr;
    std::vector<Vec3> offsets;  // of every body; only the static ones are compared
    int samples = 0;
    std::array<int, 3> n{};
    std::array<Field, 4> alpha, phi;
    std::array<std::vector<int>, 4> nearest;
    std::array<Field, 3> ub;
    bool any = false;
    bool valid = false;
    bool have_region = false;
    geometry::Aabb region;  // moving parts' bounds at the last call (world)
    // Boxes whose value stands while the moving bodies travel little (see update_ibm):
    // per box array, what the value is (0: none kept, 1: outside every moving part, the
    // static value; 2: inside the one moving body) and up to which `path` it stands.
    std::array<std::vector<unsigned char>, 4> kept_kind;
    std::array<std::vector<double>, 4> kept_until;
    double path = 0;                 // the moving bodies' travel summed over the calls [m]
    std::vector<Vec3> path_offsets;  // the body offsets at the last call
  } cache;
  bool keep_far = true;  // use kept_kind (false: evaluate every box of the region; tests)
  long kept_boxes = 0;   // boxes of the region whose value was kept in the last update
};

// Recomputes the fractions for `frame` if the bodies have moved (or on first use).
// Returns true when they were recomputed. `samples` = n of the n^3 sub-samples (>= 1).
bool update_ibm(const MacGrid& g, const geometry::Scene::Frame& frame, int samples, IbmFractions& ibm);

}  // namespace cgdem::fluid
