// Capped cone (a frustum; one radius may be 0): the solid of revolution of the trapezoid
// {0 <= t <= L, 0 <= rho <= r0 + (r1 - r0) t / L} about the axis from p0 (t = 0) to p1
// (t = L). Its exact signed distance is the distance, in the half-plane (rho, t) of the
// point, to the trapezoid's three outer edges: the caps t = 0, rho <= r0 and t = L,
// rho <= r1, and the slanted side. (The trapezoid mirrored across the axis is convex, and
// for rho >= 0 its mirrored edges are never the nearer ones, so these three suffice.)
// Inside, the distance is minus the nearest edge's, with that edge's outward normal as
// gradient; outside, the gradient points from the nearest point of the edges to x.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/shape.hpp"

namespace cgdem::geometry {

namespace {

struct Point2 {
  double r, t;  // rho, t
};

// Nearest point of the segment a-b to p (a = b allowed).
Point2 nearest_on_segment(Point2 p, Point2 a, Point2 b) {
  const double dr = b.r - a.r, dt = b.t - a.t, len2 = dr * dr + dt * dt;
  const double s = len2 > 0 ? std::clamp(((p.r - a.r) * dr + (p.t - a.t) * dt) / len2, 0.0, 1.0) : 0.0;
  return {a.r + s * dr, a.t + s * dt};
}

class Cone final : public Shape {
 public:
  Cone(const Vec3& p0, const Vec3& p1, double r0, double r1) : p0_(p0), p1_(p1), r0_(r0), r1_(r1) {
    const Vec3 a = p1 - p0;
    len_ = norm(a);
    if (!(len_ > 0) || !(r0 >= 0) || !(r1 >= 0) || !(r0 + r1 > 0))
      throw std::invalid_argument("cone needs p0 != p1, radii >= 0 and not both 0");
    axis_ = a / len_;
    // Outward normal of the slanted side in (rho, t): perpendicular to (r1 - r0, L).
    const double s = std::hypot(len_, r1 - r0);
    side_n_ = {len_ / s, -(r1 - r0) / s};
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
    const Point2 q{rho, t};
    // The three edges: bottom cap, slanted side, top cap; nearest point of each.
    const Point2 ends[3][2] = {{{0, 0}, {r0_, 0}}, {{r0_, 0}, {r1_, len_}}, {{r1_, len_}, {0, len_}}};
    const Point2 normals[3] = {{0, -1}, side_n_, {0, 1}};
    int best = 1;  // the side first: it wins ties at a pointed end
    double best_d2 = INFINITY;
    Point2 nearest{};
    for (int k : {1, 0, 2}) {
      const Point2 n = nearest_on_segment(q, ends[k][0], ends[k][1]);
      const double d2 = (q.r - n.r) * (q.r - n.r) + (q.t - n.t) * (q.t - n.t);
      if (d2 < best_d2) best = k, best_d2 = d2, nearest = n;
    }
    const double d = std::sqrt(best_d2);
    const bool inside = t > 0 && t < len_ && rho < r0_ + (r1_ - r0_) * t / len_;
    Point2 g2;
    if (inside || !(d > 0))
      g2 = normals[best];
    else
      g2 = {(q.r - nearest.r) / d, (q.t - nearest.t) / d};
    g = g2.r * er + g2.t * axis_;
    return inside ? -d : d;
  }
  Aabb bounds() const override {
    Vec3 e;  // half-extent of a unit disk normal to the axis, per coordinate
    for (int i = 0; i < 3; ++i) e[i] = std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i]));
    return {cmin(p0_ - r0_ * e, p1_ - r1_ * e), cmax(p0_ + r0_ * e, p1_ + r1_ * e)};
  }
  std::string describe() const override {
    return fmt::format("cone(p0=[{:g}, {:g}, {:g}], p1=[{:g}, {:g}, {:g}], radius0={:g}, radius1={:g})", p0_.x, p0_.y,
                       p0_.z, p1_.x, p1_.y, p1_.z, r0_, r1_);
  }

 private:
  Vec3 perpendicular() const {
    const Vec3 t = std::fabs(axis_.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 c = cross(axis_, t);
    return c / norm(c);
  }
  Vec3 p0_, p1_, axis_;
  double r0_, r1_, len_ = 0;
  Point2 side_n_{};
};

}  // namespace

ShapePtr make_cone(const Vec3& p0, const Vec3& p1, double r0, double r1) {
  return std::make_shared<Cone>(p0, p1, r0, r1);
}

}  // namespace cgdem::geometry
