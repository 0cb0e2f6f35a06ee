// Ring (a thick-walled tube, or a plate with a round hole): the solid of revolution of the
// rectangle {r_in <= rho <= r_out, 0 <= t <= L} about the axis from p0 (t = 0) to p1 (t = L).
// Its exact signed distance is the distance, in the half-plane (rho, t) of the point, to that
// rectangle: the rectangle lies at rho >= r_in > 0, so the half-plane's distance is the 3D
// one (no point of the mirrored half-plane is nearer). A round orifice in a flat floor is a
// ring with r_out beyond the bin's corners; a round bin's wall is a ring with r_in the bin's
// radius. The difference of a box and a cylinder (`make_difference`) gives the same solid but
// only a bound on the distance near the hole's rim (max of the two, not the distance to the
// rim's circle), which is where a discharging particle touches the orifice.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/shape.hpp"

namespace cgdem::geometry {

namespace {

std::string v3(const Vec3& v) { return fmt::format("[{:g}, {:g}, {:g}]", v.x, v.y, v.z); }

class Ring final : public Shape {
 public:
  Ring(const Vec3& p0, const Vec3& p1, double r_in, double r_out) : p0_(p0), p1_(p1), r_in_(r_in), r_out_(r_out) {
    const Vec3 a = p1 - p0;
    len_ = norm(a);
    if (!(len_ > 0) || !(r_in > 0) || !(r_out > r_in)) throw std::invalid_argument("ring needs p0 != p1 and 0 < radius_inner < radius_outer");
    axis_ = a / len_;
  }
  double distance(const Vec3& x) const override {
    Vec3 g;
    return distance_gradient(x, g);
  }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    const Vec3 p = x - p0_;
    const double t = dot(p, axis_);
    const Vec3 radial = p - t * axis_;
    const double rho = norm(radial);
    const Vec3 er = rho > 0 ? radial / rho : perpendicular();
    // Offsets from the rectangle's centre line, as for a 2D box of half-sizes hr, ht.
    const double rc = 0.5 * (r_in_ + r_out_), hr = 0.5 * (r_out_ - r_in_), tc = 0.5 * len_;
    const double sr = rho < rc ? -1.0 : 1.0, st = t < tc ? -1.0 : 1.0;
    const double qr = std::fabs(rho - rc) - hr, qt = std::fabs(t - tc) - tc;
    if (qr > 0 || qt > 0) {  // outside: from the nearest point of the rectangle
      const double a = std::max(qr, 0.0), b = std::max(qt, 0.0), d = std::hypot(a, b);
      g = (sr * a / d) * er + (st * b / d) * axis_;
      return d;
    }
    if (qr >= qt) {  // inside: the nearest side
      g = sr * er;
      return qr;
    }
    g = st * axis_;
    return qt;
  }
  Aabb bounds() const override {
    Vec3 e;  // half-extent of a unit disk normal to the axis, per coordinate
    for (int i = 0; i < 3; ++i) e[i] = r_out_ * std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i]));
    return {cmin(p0_, p1_) - e, cmax(p0_, p1_) + e};
  }
  std::string describe() const override {
    return fmt::format("ring(p0={}, p1={}, radius_inner={:g}, radius_outer={:g})", v3(p0_), v3(p1_), r_in_, r_out_);
  }

 private:
  Vec3 perpendicular() const {
    const Vec3 t = std::fabs(axis_.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 c = cross(axis_, t);
    return c / norm(c);
  }
  Vec3 p0_, p1_, axis_;
  double r_in_, r_out_, len_;
};

}  // namespace

ShapePtr make_ring(const Vec3& p0, const Vec3& p1, double r_in, double r_out) {
  return std::make_shared<Ring>(p0, p1, r_in, r_out);
}

}  // namespace cgdem::geometry
