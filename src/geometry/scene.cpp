#include "geometry/scene.hpp"

#include <fmt/format.h>

#include <cmath>

namespace cgdem::geometry {

int Scene::add_body(const std::string& name, Motion motion) {
  bodies_.push_back({name, std::move(motion), {}});
  return static_cast<int>(bodies_.size() - 1);
}

int Scene::add_part(int body, const std::string& name, ShapePtr shape) {
  parts_.push_back({name, std::move(shape), body});
  bodies_.at(body).parts.push_back(static_cast<int>(parts_.size() - 1));
  return static_cast<int>(parts_.size() - 1);
}

Scene::Frame Scene::at(double t) const {
  Frame f;
  f.scene = this;
  f.t = t;
  for (const auto& b : bodies_) {
    f.offset.push_back(b.motion.displacement(t));
    f.velocity.push_back(b.motion.velocity(t));
  }
  return f;
}

std::string Scene::describe() const {
  std::string s;
  for (const auto& b : bodies_) {
    s += fmt::format("body '{}'{}\n", b.name, b.motion.is_static() ? "" : " (moving)");
    for (int p : b.parts) s += fmt::format("  part '{}': {}\n", parts_[p].name, parts_[p].shape->describe());
  }
  return s;
}

double Scene::Frame::part_distance(int part, const Vec3& x, Vec3& grad) const {
  const Part& p = scene->parts()[part];
  return p.shape->distance_gradient(x - offset[p.body], grad);
}

double Scene::Frame::part_distance(int part, const Vec3& x) const {
  const Part& p = scene->parts()[part];
  return p.shape->distance(x - offset[p.body]);
}

bool Scene::same_static_placement(const std::vector<Vec3>& a, const std::vector<Vec3>& b) const {
  if (a.size() != bodies_.size() || b.size() != bodies_.size()) return false;
  for (size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].motion.is_static() && !(a[i] == b[i])) return false;
  return true;
}

Aabb Scene::Frame::part_bounds(int part) const {
  const Part& p = scene->parts()[part];
  return p.shape->bounds().shifted(offset[p.body]);
}

double Scene::Frame::phi(const Vec3& x) const {
  double m = INFINITY;
  for (size_t i = 0; i < scene->parts().size(); ++i) m = std::min(m, part_distance(static_cast<int>(i), x));
  return m;
}

Vec3 Scene::Frame::wall_velocity(const Vec3& x) const {
  double m = INFINITY;
  Vec3 u{};
  for (size_t i = 0; i < scene->parts().size(); ++i) {
    double d = part_distance(static_cast<int>(i), x);
    if (d < m) {
      m = d;
      u = part_velocity(static_cast<int>(i));
    }
  }
  return u;
}

double Scene::Frame::solid_fraction(const Vec3& lo, const Vec3& hi, int n) const {
  Vec3 c = 0.5 * (lo + hi);
  double half_diag = 0.5 * norm(hi - lo);
  double pc = phi(c);
  if (pc >= half_diag) return 0.0;
  if (pc <= -half_diag) return 1.0;
  int inside = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec3 x{lo.x + (i + 0.5) * (hi.x - lo.x) / n, lo.y + (j + 0.5) * (hi.y - lo.y) / n,
               lo.z + (k + 0.5) * (hi.z - lo.z) / n};
        if (phi(x) < 0) ++inside;
      }
  return static_cast<double>(inside) / (n * n * n);
}

}  // namespace cgdem::geometry
