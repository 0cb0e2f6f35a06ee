// The die-filling geometry of the paper (section 3; docs/model.md, Die filling), built from
// convex parts so that every concave corner is two separate wall contacts.
//
//   x along the shoe's travel, z up; the table top is at z = table_top.
//   table   : the slab [z_floor_top, table_top] with the die mouth cut out (die side walls)
//   floor   : below the deepest die floor
//   step    : the raised floor of the shallow section (type 1: shallow on the left, the
//             side the shoe reaches first; type 2: shallow on the right)
//   shoe    : four side walls around the cavity (optional lid), sliding along +x
// Default dimensions: domain 84 x 42 x 30 mm, die mouth 10 x 30 mm at x = 37..47 mm,
// deep 12 mm, shallow 7 mm, step in the middle, cavity 10 x 30 x 10 mm whose leading edge
// starts 5 mm before the mouth, so that (shoe at 0.1 m/s from t = 0) the die starts to
// open at 0.05 s, is half covered at 0.10 s, aligned at 0.15 s and closed at 0.25 s,
// as in the paper's timeline. The shoe's walls are 15 mm thick and it slides on the
// table (gap 0): the die is then covered by the shoe's body at every moment except
// through the cavity, before 0.05 s and after 0.25 s included (the paper's die "opens" at
// 0.05 s and "closes" at 0.25 s, and builds pressure from the start); 15 mm is the
// thinnest wall that covers the whole mouth from t = 0 to t = 0.30 s. With thinner walls
// or a gap, the die vents to the room beside the shoe. The table top lies at 14.4 mm, a
// plane of the paper's 0.6 mm air grid (24 cells), so that no air cell holds both the
// sliding shoe and the static table (sliding_plane_warning below says why)
// (validation/die_filling/README.md, the geometry study).
#pragma once
#include <string>

#include "core/config.hpp"
#include "geometry/scene.hpp"

namespace cgdem::geometry {

struct DieFillingParams {
  int die_type = 1;                            // 1: deep section right, 2: deep section left
  Vec3 domain_lo{0, 0, 0}, domain_hi{84e-3, 42e-3, 30e-3};
  double table_top = 14.4e-3;                      // 24 cells of 0.6 mm: the shoe slides on a grid plane
  double mouth_x0 = 37e-3, mouth_length = 10e-3;   // along x
  double mouth_y0 = 6e-3, mouth_width = 30e-3;     // along y
  double deep_depth = 12e-3, shallow_depth = 7e-3;
  double step_fraction = 0.5;                      // share of the mouth length that is shallow
  double floor_thickness = 2e-3;
  Vec3 cavity_size{10e-3, 30e-3, 10e-3};
  double cavity_x0 = 22e-3;                        // leading (right) edge at x0 + length = 32 mm
  double shoe_wall = 15e-3;                        // covers the mouth outside the cavity
  double shoe_gap = 0.0;                           // between shoe and table: sliding on it, sealed
  bool shoe_lid = false;
  double shoe_speed = 0.1;                         // [m/s] along +x
  double shoe_start = 0.0;                         // time the shoe starts [s]
  double shoe_ramp = 1e-3;                         // time to reach full speed [s]

  // Cavity interior at t = 0 (insertion region).
  Vec3 cavity_lo() const { return {cavity_x0, mouth_y0, table_top}; }
  Vec3 cavity_hi() const { return {cavity_x0 + cavity_size.x, mouth_y0 + cavity_size.y, table_top + cavity_size.z}; }
  // The shoe's prescribed motion: at rest until shoe_start, then ramped to shoe_speed along +x.
  Motion shoe_motion() const {
    return Motion({shoe_start, shoe_start + shoe_ramp}, {Vec3{}, Vec3{shoe_speed, 0, 0}});
  }
};

DieFillingParams read_die_filling(const Section& s);

// With air on a grid of spacing dx whose z planes lie at origin_z + k dx: a warning when the
// planes where the sliding shoe meets the table (the table top, and the shoe's bottom
// table_top + shoe_gap) do not lie on grid planes; empty when they do. The air cells that
// straddle such a plane hold both the moving shoe and the static table or the die's air, and
// the volume-weighted immersed boundary moves their air at the shoe's velocity, also
// through the contact: a conveyor of up to shoe_speed x dx x cavity width of air out of
// or into the die (measured on Case 1-3: 1.8e-6 m^3/s, the shoe's 0.1 m/s x 0.6 mm x 30 mm,
// validation/die_filling/README.md).
std::string sliding_plane_warning(const DieFillingParams& p, double origin_z, double dx);
void add_die_filling(Scene& scene, const DieFillingParams& p);

}  // namespace cgdem::geometry
