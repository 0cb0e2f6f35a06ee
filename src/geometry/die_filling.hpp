// The die-filling geometry of the paper (section 3; physics.md section 4), built from
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
// as in the paper's timeline.
#pragma once
#include "core/config.hpp"
#include "geometry/scene.hpp"

namespace cgdem::geometry {

struct DieFillingParams {
  int die_type = 1;                            // 1: deep section right, 2: deep section left
  Vec3 domain_lo{0, 0, 0}, domain_hi{84e-3, 42e-3, 30e-3};
  double table_top = 14e-3;
  double mouth_x0 = 37e-3, mouth_length = 10e-3;   // along x
  double mouth_y0 = 6e-3, mouth_width = 30e-3;     // along y
  double deep_depth = 12e-3, shallow_depth = 7e-3;
  double step_fraction = 0.5;                      // share of the mouth length that is shallow
  double floor_thickness = 2e-3;
  Vec3 cavity_size{10e-3, 30e-3, 10e-3};
  double cavity_x0 = 22e-3;                        // leading (right) edge at x0 + length = 32 mm
  double shoe_wall = 3e-3;
  double shoe_gap = 0.1e-3;                        // between shoe and table
  bool shoe_lid = false;
  double shoe_speed = 0.1;                         // [m/s] along +x
  double shoe_start = 0.0;                         // time the shoe starts [s]
  double shoe_ramp = 1e-3;                         // time to reach full speed [s]

  // Cavity interior at t = 0 (insertion region).
  Vec3 cavity_lo() const { return {cavity_x0, mouth_y0, table_top}; }
  Vec3 cavity_hi() const { return {cavity_x0 + cavity_size.x, mouth_y0 + cavity_size.y, table_top + cavity_size.z}; }
};

DieFillingParams read_die_filling(const Section& s);
void add_die_filling(Scene& scene, const DieFillingParams& p);

}  // namespace cgdem::geometry
