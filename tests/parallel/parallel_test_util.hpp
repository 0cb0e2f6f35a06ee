// Helpers of the decomposition and migration tests (serial and MPI): parcels whose every
// field holds a value no other parcel or field shares, contact histories that follow
// from the two ids, and bitwise comparisons.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "geometry/scene.hpp"
#include "geometry/shape.hpp"
#include "parallel/parcel_fields.hpp"
#include "particles/neighbor_list.hpp"

namespace cgdem::test {

inline Species powder_l3() { return {"powder", 125e-6, 3.0, 1500.0}; }

// Sets every field of parcel i to values that depend on `seed` and on the field, then
// puts back what the neighbour search and the mass totals need to be physical.
inline void set_distinct(Particles& p, size_t i, int64_t seed, const Species& s) {
  int f = 0;
  parallel::for_each_field(p, [&](auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::value_type;
    const double base = 100.0 * static_cast<double>(seed) + ++f;
    if constexpr (std::is_same_v<T, Vec3>)
      field[i] = {base + 0.125, base + 0.25, base + 0.5};
    else
      field[i] = static_cast<T>(base);
  });
  p.species[i] = 0;
  p.radius[i] = 0.5 * s.diameter();
  p.inv_mass[i] = 1.0 / s.mass();
  p.inv_inertia[i] = 1.0 / s.inertia();
}

// Appends a parcel of id `id` at x with every other field distinct (set_distinct).
inline void add_distinct(Particles& p, int64_t id, const Vec3& x, const Species& s) {
  p.add(id, 0, s, x);
  set_distinct(p, p.size() - 1, id + 1, s);
  p.id.back() = id;
  p.x.back() = x;
}

// The bytes of every field of parcel i, in declaration order.
inline std::string bytes_of(const Particles& p, size_t i) {
  std::string b;
  parallel::for_each_field(p, [&](const auto& field) {
    b.append(reinterpret_cast<const char*>(&field[i]), sizeof(field[i]));
  });
  return b;
}

inline bool same_bits(const contact::History& a, const contact::History& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// A non-empty history for the pair (a, b), a < b, in a's frame; distinct per pair.
inline contact::History pair_history(int64_t a, int64_t b) {
  const double s = 1e-7 * static_cast<double>(1 + a) + 1e-9 * static_cast<double>(b);
  return {{s, -2 * s, 0.5 * s}, {3e3 * s, 1e3 * s, -4e3 * s}, -1e2 * s, 7e5 * s};
}
inline contact::History wall_history(int64_t id) { return pair_history(id, -1); }

// The history of list entry e, in the frame of the pair's particle of lower id.
inline contact::History lower_id_frame(const Particles& p, const NeighborList& nl, int owner, int e) {
  return p.id[owner] < p.id[nl.partner[e]] ? nl.hist.get(e) : nl.hist.get(e).flipped();
}

// Gives every pair of the lists pair_history() of its ids and every wall candidate
// wall_history() of its particle, in the frames the lists keep them in.
inline void set_histories(const Particles& p, NeighborList& nl) {
  for (int i = 0; i + 1 < static_cast<int>(nl.offset.size()); ++i) {
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int64_t a = p.id[i], b = p.id[nl.partner[e]];
      nl.hist.set(e, a < b ? pair_history(a, b) : pair_history(b, a).flipped());
    }
    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e) nl.wall_hist[e] = wall_history(p.id[i]);
  }
  nl.derive();
}

// A floor z = 0 (solid below), one part.
inline geometry::Scene floor_scene() {
  geometry::Scene scene;
  const int b = scene.add_body("box", geometry::Motion{});
  scene.add_part(b, "floor", geometry::make_half_space({0, 0, 0}, {0, 0, 1}));
  return scene;
}

}  // namespace cgdem::test
