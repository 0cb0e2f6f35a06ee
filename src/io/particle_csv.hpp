// Particle initial conditions as CSV text.
//
// Format: lines starting with '#' and blank lines are ignored; the first other line is
// the header naming the columns (any order, surrounding spaces ignored):
//   x, y, z, d        required (m); d > 0 is the particle diameter
//   vx, vy, vz        optional, all three or none (m/s)
//   wx, wy, wz        optional angular velocity, all three or none (rad/s)
//   id                optional integer (default: 0-based row index)
//   species           optional integer >= 0 (default 0)
// Every data line has exactly as many fields as the header. Numbers must be finite.
// Errors throw cgdem::Error as "<file>:<line>: <what>" (line numbers from 1).
//
// The writer uses %.17g for doubles, so write -> read reproduces every value bit for bit,
// and writes atomically (see atomic_file.hpp).
#pragma once
#include <string>

#include "io/particle_table.hpp"

namespace cgdem::io {

ParticleTable read_particles_csv(const std::string& path);

// Columns written: id,species,x,y,z,d then vx,vy,vz and wx,wy,wz when present.
void write_particles_csv(const std::string& path, const ParticleTable& table);

// Same formats on in-memory text (`name` is used in error messages), for tests and tools.
ParticleTable parse_particles_csv(const std::string& text, const std::string& name);
std::string format_particles_csv(const ParticleTable& table);

}  // namespace cgdem::io
