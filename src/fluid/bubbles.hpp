// Bubbles: pockets of air inside the powder, found on the air grid.
//
// A cell is "air" when it is not mostly wall (alpha_cell < 0.5) and the powder leaves it
// nearly empty (eps >= eps_air, 0.9 by default: a packed bed has eps ~0.4, a falling
// stream 0.6-0.9). Air cells joined through their faces form regions. A region that
// reaches an open side of the domain is the room's air, not a bubble. A region that does
// not, and touches the powder somewhere (a face neighbour that is neither air nor wall),
// is a bubble: air enclosed by powder and walls. A region closed by walls alone (a sealed
// die before the cavity arrives) is not a bubble; it is counted apart as sealed air.
//
// For each bubble: its air volume sum (1 - alpha) eps dx^3 over its cells [m^3], its
// centroid (air-volume weighted) [m] and the top of its highest cell [m]. The search is
// serial and deterministic (cells visited in index order), so the result does not depend
// on the thread count; only the sorting of cells into kinds, each cell on its own, runs on
// all threads.
#pragma once
#include <vector>

#include "core/vec3.hpp"
#include "fluid/boundary.hpp"
#include "fluid/mac_grid.hpp"

namespace cgdem::fluid {

struct Bubble {
  double volume = 0;  // [m^3] of air
  Vec3 centroid{};    // [m]
  double z_top = 0;   // [m], top face of the highest cell
  double volume_above = 0;  // [m^3] of it in cells whose centre lies above z_split
  long cells = 0;
};

struct BubbleCensus {
  std::vector<Bubble> bubbles;  // largest first
  double sealed_volume = 0;     // [m^3] air in regions closed by walls only (no powder contact)
  double total_volume() const;
  double total_volume_above() const;
  const Bubble* largest() const { return bubbles.empty() ? nullptr : &bubbles.front(); }
};

// eps, alpha_cell: cell fields of grid g (interior cells are read; ghosts are not).
// Regions with fewer than min_cells cells are ignored (grid noise in a loose stream).
// z_split: the height above which a bubble's volume is also counted apart (the table top:
// the part of the bubble that has risen into the shoe).
BubbleCensus find_bubbles(const MacGrid& g, const Field& eps, const Field& alpha_cell, const FluidBoundary& bc,
                          double eps_air = 0.9, long min_cells = 1, double z_split = 1e300);

}  // namespace cgdem::fluid
