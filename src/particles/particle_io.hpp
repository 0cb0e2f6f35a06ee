// Conversion between the particle storage and the file exchange table (io/particle_table).
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

#include "io/particle_table.hpp"
#include "particles/particles.hpp"

namespace cgdem {

// The first n parcels of p (all by default; a rank's owned parcels come before its
// ghosts), in increasing id: a snapshot does not depend on the order in which the
// neighbour lists keep the parcels, nor on how many ranks ran.
io::ParticleTable to_table(const Particles& p, size_t n = std::numeric_limits<size_t>::max());
// Appends the table's particles as species `species_index`; every row's diameter must match
// that species' parcel diameter l d_O (relative 1e-6); throws cgdem::Error otherwise.
void append_table(Particles& p, const std::vector<Species>& species, const io::ParticleTable& t,
                  int species_index, const std::string& source);

}  // namespace cgdem
