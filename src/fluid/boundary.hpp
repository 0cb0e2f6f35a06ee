// Domain-face boundary conditions of the air phase and the explicit ghost-layer fills.
//
// Sides are numbered s = 2 d + h (d = axis, h = 0 low / 1 high): -x, +x, -y, +y, -z, +z.
//
//   Wall      no slip with a prescribed wall velocity U_w (a moving lid is a Wall with a
//             tangential U_w). Normal face value u_d = U_w,d on the boundary face; ghosts
//             mirror so that the wall value is the face average:
//               normal      u(-m)   = 2 U_w,d - u(m)           (m = 1, 2)
//               tangential  u_t(-1-m) = 2 U_w,t - u_t(m)        (m = 0, 1)
//             pressure and eps: zero normal gradient, s(-1-m) = s(m).
//   Open      fixed pressure p_open, zero normal gradient of velocity (inflow or outflow):
//               normal      u(-m) = u(0) (the boundary face itself is an unknown),
//               tangential  u_t(-1-m) = u_t(m),
//               pressure    p(-1-m) = 2 p_open - p(m)  (p = p_open on the face),
//               eps         s(-1-m) = s(m).
//   Periodic  both sides of the axis; face n is the image of face 0, ghosts wrap.
//
// Fills run axis by axis over the whole padded extent of the other axes, so edges and
// corners end up consistent. In an MPI decomposition these become halo exchanges on the
// faces between sub-domains and stay as they are on the physical boundary.
#pragma once
#include <array>
#include <string>

#include "fluid/mac_grid.hpp"

namespace cgdem::fluid {

enum class BcType { Wall, Open, Periodic };

struct SideBc {
  BcType type = BcType::Wall;
  Vec3 wall_velocity{};  // [m/s], Wall only
  double pressure = 0;   // [Pa], Open only
};

using FluidBoundary = std::array<SideBc, 6>;

// All six sides of the same type (convenience for tests and simple cases).
FluidBoundary uniform_boundary(BcType t);
// Throws cgdem::Error if a periodic side is paired with a non-periodic one.
void validate_boundary(const FluidBoundary& bc);
std::string describe_boundary(const FluidBoundary& bc);

// Range [first, last) of the face indices along axis d that are unknowns of component d:
// a Wall boundary face is prescribed, an Open one is computed, a periodic face n is an image.
std::array<int, 2> active_face_range(const MacGrid& g, const FluidBoundary& bc, int d);

// Ghost layers (and prescribed boundary faces) of the three velocity components.
void fill_velocity_ghosts(const MacGrid& g, const FluidBoundary& bc, Field& u, Field& v, Field& w);
// Ghost layers of one velocity component (used for source or work arrays of the same layout).
void fill_velocity_component_ghosts(const MacGrid& g, const FluidBoundary& bc, int d, Field& f);

enum class ScalarKind { Pressure, ZeroGradient };
// Ghost layers of a cell-centred scalar.
void fill_scalar_ghosts(const MacGrid& g, const FluidBoundary& bc, Field& s, ScalarKind kind);

}  // namespace cgdem::fluid
