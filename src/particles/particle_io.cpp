#include "particles/particle_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cgdem {

io::ParticleTable to_table(const Particles& p, size_t n) {
  std::vector<size_t> order(std::min(n, p.size()));
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p.id[a] < p.id[b]; });
  io::ParticleTable t;
  for (size_t i : order) {
    t.id.push_back(p.id[i]);
    t.species.push_back(p.species[i]);
    t.x.push_back(p.x[i]);
    t.v.push_back(p.v[i]);
    t.omega.push_back(p.omega[i]);
    t.d.push_back(2 * p.radius[i]);
  }
  return t;
}

void append_table(Particles& p, const std::vector<Species>& species, const io::ParticleTable& t,
                  int species_index, const std::string& source) {
  t.validate(source);
  int64_t next_id = 0;  // ids of a file appended to existing particles are shifted past them
  for (auto id : p.id) next_id = std::max(next_id, id + 1);
  const int s = species_index;
  const Species& sp = species.at(s);
  for (size_t i = 0; i < t.size(); ++i) {
    if (std::fabs(t.d[i] - sp.diameter()) > 1e-6 * sp.diameter())
      throw Error(fmt::format("{}: particle {}: diameter {:g} m does not match species '{}' (l d_O = {:g} m)", source, i,
                              t.d[i], sp.name, sp.diameter()));
    p.add(next_id + (t.id.empty() ? static_cast<int64_t>(i) : t.id[i]), s, sp, t.x[i],
          t.has_velocity() ? t.v[i] : Vec3{}, t.has_omega() ? t.omega[i] : Vec3{});
  }
}

}  // namespace cgdem
