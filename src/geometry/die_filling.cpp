#include "geometry/die_filling.hpp"

#include <fmt/format.h>

#include <cmath>

namespace cgdem::geometry {

DieFillingParams read_die_filling(const Section& s) {
  DieFillingParams p;
  p.die_type = static_cast<int>(s.integer_or("die_type", p.die_type, Range::closed(1, 2)));
  p.domain_lo = s.vec3_or("domain_min", p.domain_lo);
  p.domain_hi = s.vec3_or("domain_max", p.domain_hi);
  p.table_top = s.number_or("table_top", p.table_top);
  p.mouth_x0 = s.number_or("mouth_x0", p.mouth_x0);
  p.mouth_length = s.number_or("mouth_length", p.mouth_length, Range::positive());
  p.mouth_y0 = s.number_or("mouth_y0", p.mouth_y0);
  p.mouth_width = s.number_or("mouth_width", p.mouth_width, Range::positive());
  p.deep_depth = s.number_or("deep_depth", p.deep_depth, Range::positive());
  p.shallow_depth = s.number_or("shallow_depth", p.shallow_depth, Range::positive());
  p.step_fraction = s.number_or("step_fraction", p.step_fraction, Range::closed(0, 1));
  p.floor_thickness = s.number_or("floor_thickness", p.floor_thickness, Range::positive());
  p.cavity_size = s.vec3_or("cavity_size", p.cavity_size);
  p.cavity_x0 = s.number_or("cavity_x0", p.cavity_x0);
  p.shoe_wall = s.number_or("shoe_wall", p.shoe_wall, Range::positive());
  p.shoe_gap = s.number_or("shoe_gap", p.shoe_gap, Range::non_negative());
  p.shoe_lid = s.boolean_or("shoe_lid", p.shoe_lid);
  p.shoe_speed = s.number_or("shoe_speed", p.shoe_speed);
  p.shoe_start = s.number_or("shoe_start", p.shoe_start);
  p.shoe_ramp = s.number_or("shoe_ramp", p.shoe_ramp, Range::positive());
  if (p.shallow_depth > p.deep_depth) s.fail("shallow_depth", "must not exceed deep_depth");
  if (p.table_top - p.deep_depth - p.floor_thickness < p.domain_lo.z - 1e-12)
    s.fail("deep_depth", "the die floor lies below the domain (table_top - deep_depth - floor_thickness < domain_min z)");
  for (int a = 0; a < 3; ++a)
    if (!(p.cavity_size[a] > 0)) s.fail("cavity_size", "every size must be > 0");
  return p;
}

std::string sliding_plane_warning(const DieFillingParams& p, double origin_z, double dx) {
  auto off_grid = [&](double z) {
    const double k = (z - origin_z) / dx;
    return std::abs(k - std::round(k)) > 1e-6;
  };
  const double bottom = p.table_top + p.shoe_gap;
  std::string w;
  if (off_grid(p.table_top) || off_grid(bottom)) {
    w = fmt::format("the shoe slides on z = {:g} mm", 1e3 * bottom);
    if (p.shoe_gap > 0) w += fmt::format(" above the table top z = {:g} mm", 1e3 * p.table_top);
    w += fmt::format(", not on a plane of the {:g} mm air grid: the air cells across it move with the shoe through "
                     "the contact (a leak of up to {:.2g} m^3/s into or out of the die)",
                     1e3 * dx, std::abs(p.shoe_speed) * dx * p.cavity_size.y);
    if (p.shoe_gap == 0)
      w += fmt::format("; table_top = {:g} or {:g} mm puts it on the grid",
                       1e3 * (origin_z + dx * std::floor((p.table_top - origin_z) / dx)),
                       1e3 * (origin_z + dx * std::ceil((p.table_top - origin_z) / dx)));
    else
      w += "; a gap thinner than a cell cannot be put on the grid (shoe_gap = 0 seals it)";
  }
  return w;
}

void add_die_filling(Scene& scene, const DieFillingParams& p) {
  const double big = 1.0;  // beyond the domain, so the table has no edges inside it
  const double z_deep = p.table_top - p.deep_depth, z_shallow = p.table_top - p.shallow_depth;
  const double x1 = p.mouth_x0 + p.mouth_length, y1 = p.mouth_y0 + p.mouth_width;

  int fixed = scene.add_body("table", Motion{});
  auto slab = make_box({-big, -big, z_deep}, {big, big, p.table_top});
  auto mouth = make_box({p.mouth_x0, p.mouth_y0, z_deep - 1e-3}, {x1, y1, p.table_top + 1e-3});
  scene.add_part(fixed, "table", make_difference(slab, mouth));
  scene.add_part(fixed, "die floor", make_box({-big, -big, z_deep - p.floor_thickness}, {big, big, z_deep}));
  const double xs = p.mouth_length * p.step_fraction;
  if (xs > 0 && p.shallow_depth < p.deep_depth) {
    Vec3 lo{p.mouth_x0, p.mouth_y0, z_deep}, hi{p.mouth_x0 + xs, y1, z_shallow};
    if (p.die_type == 2) lo.x = x1 - xs, hi.x = x1;
    // Extend under the die walls so the step has no gap at the side walls.
    lo.y -= 1e-3, hi.y += 1e-3;
    (p.die_type == 1 ? lo.x : hi.x) += (p.die_type == 1 ? -1e-3 : 1e-3);
    scene.add_part(fixed, "step", make_box(lo, hi));
  }

  int shoe = scene.add_body("shoe", p.shoe_motion());
  const Vec3 c0 = p.cavity_lo(), c1 = p.cavity_hi();
  const double w = p.shoe_wall, z0 = p.table_top + p.shoe_gap, z1 = c1.z;
  scene.add_part(shoe, "shoe left", make_box({c0.x - w, c0.y - w, z0}, {c0.x, c1.y + w, z1}));
  scene.add_part(shoe, "shoe right", make_box({c1.x, c0.y - w, z0}, {c1.x + w, c1.y + w, z1}));
  scene.add_part(shoe, "shoe front", make_box({c0.x, c0.y - w, z0}, {c1.x, c0.y, z1}));
  scene.add_part(shoe, "shoe back", make_box({c0.x, c1.y, z0}, {c1.x, c1.y + w, z1}));
  if (p.shoe_lid) scene.add_part(shoe, "shoe lid", make_box({c0.x - w, c0.y - w, z1}, {c1.x + w, c1.y + w, z1 + w}));
}

}  // namespace cgdem::geometry
