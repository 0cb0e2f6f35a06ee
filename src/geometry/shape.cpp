#include "geometry/shape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cgdem::geometry {

double Aabb::distance(const Vec3& x) const {
  Vec3 d = cmax(cmax(lo - x, x - hi), Vec3{0, 0, 0});
  // Unbounded boxes: inf - finite comparisons are fine; clamp NaN from inf-inf.
  for (int i = 0; i < 3; ++i)
    if (std::isnan(d[i])) d[i] = 0;
  return norm(d);
}

namespace {

std::string v3(const Vec3& v) { return fmt::format("[{:g}, {:g}, {:g}]", v.x, v.y, v.z); }

class HalfSpace final : public Shape {
 public:
  HalfSpace(const Vec3& p, const Vec3& n) : p_(p), n_(n / norm(n)) {}
  double distance(const Vec3& x) const override { return dot(x - p_, n_); }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    g = n_;
    return dot(x - p_, n_);
  }
  Aabb bounds() const override {
    Aabb b;  // unbounded, except along an axis-aligned normal
    for (int i = 0; i < 3; ++i) {
      if (n_[i] == 1.0) b.hi[i] = p_[i];
      if (n_[i] == -1.0) b.lo[i] = p_[i];
    }
    return b;
  }
  std::string describe() const override { return fmt::format("halfspace(point={}, normal={})", v3(p_), v3(n_)); }

 private:
  Vec3 p_, n_;
};

class Box final : public Shape {
 public:
  Box(const Vec3& lo, const Vec3& hi) : c_(0.5 * (lo + hi)), h_(0.5 * (hi - lo)), lo_(lo), hi_(hi) {}
  double distance(const Vec3& x) const override {
    Vec3 p = x - c_;
    Vec3 q{std::fabs(p.x) - h_.x, std::fabs(p.y) - h_.y, std::fabs(p.z) - h_.z};
    double inside = std::min(std::max({q.x, q.y, q.z}), 0.0);
    return norm(cmax(q, Vec3{0, 0, 0})) + inside;
  }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    Vec3 p = x - c_;
    Vec3 s{p.x < 0 ? -1.0 : 1.0, p.y < 0 ? -1.0 : 1.0, p.z < 0 ? -1.0 : 1.0};
    Vec3 q{std::fabs(p.x) - h_.x, std::fabs(p.y) - h_.y, std::fabs(p.z) - h_.z};
    if (q.x > 0 || q.y > 0 || q.z > 0) {  // outside: gradient along the clamped offset
      Vec3 o = cmax(q, Vec3{0, 0, 0});
      double d = norm(o);
      g = Vec3{s.x * o.x, s.y * o.y, s.z * o.z} / d;
      return d;
    }
    // inside: the nearest face
    int a = (q.x >= q.y && q.x >= q.z) ? 0 : (q.y >= q.z ? 1 : 2);
    g = Vec3{};
    g[a] = s[a];
    return q[a];
  }
  Aabb bounds() const override { return {lo_, hi_}; }
  std::string describe() const override { return fmt::format("box(min={}, max={})", v3(lo_), v3(hi_)); }
  bool axis_separable() const override { return true; }
  // distance() < 0 iff max(q) < 0, q = |x - c| - h per axis (the outside part is 0 then)
  bool inside_along(int axis, double v) const override { return std::fabs(v - c_[axis]) - h_[axis] < 0; }

 private:
  Vec3 c_, h_, lo_, hi_;
};

class Cylinder final : public Shape {
 public:
  Cylinder(const Vec3& p0, const Vec3& p1, double r) : p0_(p0), p1_(p1), r_(r) {
    Vec3 a = p1 - p0;
    len_ = norm(a);
    if (!(len_ > 0) || !(r > 0)) throw std::invalid_argument("cylinder needs p0 != p1 and radius > 0");
    axis_ = a / len_;
  }
  double distance(const Vec3& x) const override {
    Vec3 g;
    return distance_gradient(x, g);
  }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    Vec3 p = x - p0_;
    double t = dot(p, axis_) - 0.5 * len_;  // axial coordinate from the middle
    Vec3 radial = p - (t + 0.5 * len_) * axis_;
    double rho = norm(radial);
    Vec3 er = rho > 0 ? radial / rho : perpendicular();
    Vec3 ea = t < 0 ? -axis_ : axis_;
    double qr = rho - r_, qa = std::fabs(t) - 0.5 * len_;
    if (qr > 0 || qa > 0) {
      double a = std::max(qr, 0.0), b = std::max(qa, 0.0), d = std::hypot(a, b);
      g = (a * er + b * ea) / d;
      return d;
    }
    if (qr >= qa) {
      g = er;
      return qr;
    }
    g = ea;
    return qa;
  }
  Aabb bounds() const override {
    Vec3 e;
    for (int i = 0; i < 3; ++i) e[i] = r_ * std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i]));
    return {cmin(p0_, p1_) - e, cmax(p0_, p1_) + e};
  }
  std::string describe() const override {
    return fmt::format("cylinder(p0={}, p1={}, radius={:g})", v3(p0_), v3(p1_), r_);
  }

 private:
  Vec3 perpendicular() const {
    Vec3 t = std::fabs(axis_.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 c = cross(axis_, t);
    return c / norm(c);
  }
  Vec3 p0_, p1_, axis_;
  double r_, len_;
};

class Sphere final : public Shape {
 public:
  Sphere(const Vec3& c, double r) : c_(c), r_(r) {}
  double distance(const Vec3& x) const override { return norm(x - c_) - r_; }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    Vec3 p = x - c_;
    double n = norm(p);
    g = n > 0 ? p / n : Vec3{0, 0, 1};
    return n - r_;
  }
  Aabb bounds() const override { return {c_ - Vec3{r_, r_, r_}, c_ + Vec3{r_, r_, r_}}; }
  std::string describe() const override { return fmt::format("sphere(centre={}, radius={:g})", v3(c_), r_); }

 private:
  Vec3 c_;
  double r_;
};

enum class Op { Union, Intersection, Difference };

class Csg final : public Shape {
 public:
  Csg(Op op, ShapePtr a, ShapePtr b) : op_(op), a_(std::move(a)), b_(std::move(b)) {}
  double distance(const Vec3& x) const override {
    double da = a_->distance(x), db = b_->distance(x);
    switch (op_) {
      case Op::Union: return std::min(da, db);
      case Op::Intersection: return std::max(da, db);
      default: return std::max(da, -db);
    }
  }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    Vec3 ga, gb;
    double da = a_->distance_gradient(x, ga), db = b_->distance_gradient(x, gb);
    switch (op_) {
      case Op::Union:
        if (da <= db) { g = ga; return da; }
        g = gb; return db;
      case Op::Intersection:
        if (da >= db) { g = ga; return da; }
        g = gb; return db;
      default:
        if (da >= -db) { g = ga; return da; }
        g = -gb; return -db;
    }
  }
  Aabb bounds() const override {
    Aabb ba = a_->bounds(), bb = b_->bounds();
    switch (op_) {
      case Op::Union: return {cmin(ba.lo, bb.lo), cmax(ba.hi, bb.hi)};
      case Op::Intersection: return {cmax(ba.lo, bb.lo), cmin(ba.hi, bb.hi)};
      default: return ba;
    }
  }
  std::string describe() const override {
    const char* n = op_ == Op::Union ? "union" : (op_ == Op::Intersection ? "intersection" : "difference");
    return fmt::format("{}({}, {})", n, a_->describe(), b_->describe());
  }

 private:
  Op op_;
  ShapePtr a_, b_;
};

class Complement final : public Shape {
 public:
  explicit Complement(ShapePtr a) : a_(std::move(a)) {}
  double distance(const Vec3& x) const override { return -a_->distance(x); }
  double distance_gradient(const Vec3& x, Vec3& g) const override {
    double d = a_->distance_gradient(x, g);
    g = -g;
    return -d;
  }
  Aabb bounds() const override { return {}; }
  std::string describe() const override { return fmt::format("complement({})", a_->describe()); }

 private:
  ShapePtr a_;
};

}  // namespace

ShapePtr make_half_space(const Vec3& p, const Vec3& n) {
  if (!(norm(n) > 0)) throw std::invalid_argument("halfspace normal must be non-zero");
  return std::make_shared<HalfSpace>(p, n);
}
ShapePtr make_box(const Vec3& lo, const Vec3& hi) {
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) throw std::invalid_argument("box needs max > min on every axis");
  return std::make_shared<Box>(lo, hi);
}
ShapePtr make_cylinder(const Vec3& p0, const Vec3& p1, double r) { return std::make_shared<Cylinder>(p0, p1, r); }
ShapePtr make_sphere(const Vec3& c, double r) {
  if (!(r > 0)) throw std::invalid_argument("sphere radius must be > 0");
  return std::make_shared<Sphere>(c, r);
}
ShapePtr make_union(ShapePtr a, ShapePtr b) { return std::make_shared<Csg>(Op::Union, std::move(a), std::move(b)); }
ShapePtr make_intersection(ShapePtr a, ShapePtr b) {
  return std::make_shared<Csg>(Op::Intersection, std::move(a), std::move(b));
}
ShapePtr make_difference(ShapePtr a, ShapePtr b) {
  return std::make_shared<Csg>(Op::Difference, std::move(a), std::move(b));
}
ShapePtr make_complement(ShapePtr a) { return std::make_shared<Complement>(std::move(a)); }

}  // namespace cgdem::geometry
