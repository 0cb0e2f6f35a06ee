#include "particles/particles.hpp"

namespace cgdem {

void Particles::add(int64_t pid, int sp, const Species& s, const Vec3& pos, const Vec3& vel, const Vec3& w) {
  id.push_back(pid);
  species.push_back(sp);
  x.push_back(pos);
  v.push_back(vel);
  omega.push_back(w);
  force.emplace_back();
  torque.emplace_back();
  f_ext.emplace_back();
  drag.push_back(0);
  u_fluid.emplace_back();
  j_drag.emplace_back();
  radius.push_back(0.5 * s.diameter());
  inv_mass.push_back(1.0 / s.mass());
  inv_inertia.push_back(1.0 / s.inertia());
  e_damping.push_back(0);
  e_friction.push_back(0);
  w_walls.push_back(0);
  w_fluid.push_back(0);
}

void Particles::reorder(const std::vector<int>& order) {
  ReorderScratch scratch;
  reorder(order, scratch);
}

void Particles::reorder(const std::vector<int>& order, ReorderScratch& scratch) {
  const long n = static_cast<long>(order.size());
  for_each_field(*this, [&](auto& field) {
    auto& b = std::get<std::remove_reference_t<decltype(field)>>(scratch);
    b.resize(n);
#pragma omp parallel for schedule(static) if (n >= 4096)
    for (long i = 0; i < n; ++i) b[i] = field[order[i]];
    field.swap(b);
  });
}

void Particles::append(const Particles& other) {
  for_each_field(*this, other, [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); });
}

}  // namespace cgdem
