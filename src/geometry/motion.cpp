#include "geometry/motion.hpp"

#include <algorithm>
#include <stdexcept>

namespace cgdem::geometry {

Motion::Motion(std::vector<double> times, std::vector<Vec3> velocities)
    : times_(std::move(times)), velocities_(std::move(velocities)) {
  if (times_.empty() || times_.size() != velocities_.size())
    throw std::invalid_argument("motion needs as many velocities as times (at least one)");
  for (size_t k = 1; k < times_.size(); ++k)
    if (!(times_[k] > times_[k - 1])) throw std::invalid_argument("motion times must increase strictly");
}

Vec3 Motion::velocity(double t) const {
  if (t <= times_.front()) return velocities_.front();
  if (t >= times_.back()) return velocities_.back();
  size_t k = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();  // times_[k-1] <= t < times_[k]
  double w = (t - times_[k - 1]) / (times_[k] - times_[k - 1]);
  return (1 - w) * velocities_[k - 1] + w * velocities_[k];
}

Vec3 Motion::displacement(double t) const {
  // Integral of the piecewise-linear velocity from 0 to t (t may be negative).
  auto integral_to = [&](double s) {  // from -inf reference: integrate from times_.front()
    Vec3 x{};
    if (s <= times_.front()) return (s - times_.front()) * velocities_.front();
    for (size_t k = 1; k < times_.size() && times_[k - 1] < s; ++k) {
      double b = std::min(s, times_[k]);
      x += (b - times_[k - 1]) * 0.5 * (velocities_[k - 1] + velocity(b));
    }
    if (s > times_.back()) x += (s - times_.back()) * velocities_.back();
    return x;
  };
  return integral_to(t) - integral_to(0.0);
}

bool Motion::is_static() const {
  for (const auto& v : velocities_)
    if (!(v == Vec3{})) return false;
  return true;
}

double Motion::max_speed() const {
  double m = 0;
  for (const auto& v : velocities_) m = std::max(m, norm(v));
  return m;
}

}  // namespace cgdem::geometry
