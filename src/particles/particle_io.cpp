#include "particles/particle_io.hpp"

#include <fmt/format.h>

#include <cmath>

namespace cgdem {

io::ParticleTable to_table(const Particles& p) {
  io::ParticleTable t;
  t.id = p.id;
  t.species = p.species;
  t.x = p.x;
  t.v = p.v;
  t.omega = p.omega;
  t.d.resize(p.size());
  for (size_t i = 0; i < p.size(); ++i) t.d[i] = 2 * p.radius[i];
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
