// Health checks of a running case (particle_run.cpp): over MPI ranks each rank applies
// them to its own parcels and air cells.
#pragma once
#include <cstddef>

#include "fluid/fluid_state.hpp"
#include "geometry/scene.hpp"
#include "particles/particles.hpp"

namespace cgdem::app {

// Throws RunError naming the parcel, the step and the time when one of the first n parcels
// has a non-finite position or velocity or moves faster than max_speed (a blow-up).
void check_particles(const Particles& p, size_t n, long step, double t, double max_speed);

// Parcels among the first n whose centre lies inside a wall at time t (tunnelled).
long count_inside_walls(const geometry::Scene& scene, double t, const Particles& p, size_t n);

// Throws RunError naming the cell when the air has a non-finite pressure or a non-finite or
// runaway velocity (> max_speed) in a cell of `air` (a block of the grid: cell indices are
// given as in the whole grid, shifted by first_cell).
void check_air(const fluid::FluidState& air, double max_speed, long fluid_step, std::array<int, 3> first_cell = {});

}  // namespace cgdem::app
