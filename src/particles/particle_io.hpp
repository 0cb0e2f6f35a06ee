// Conversion between the particle storage and the file exchange table (io/particle_table).
#pragma once
#include <vector>

#include "io/particle_table.hpp"
#include "particles/particles.hpp"

namespace cgdem {

io::ParticleTable to_table(const Particles& p);
// Appends the table's particles as species `species_index`; every row's diameter must match
// that species' parcel diameter l d_O (relative 1e-6); throws cgdem::Error otherwise.
void append_table(Particles& p, const std::vector<Species>& species, const io::ParticleTable& t,
                  int species_index, const std::string& source);

}  // namespace cgdem
