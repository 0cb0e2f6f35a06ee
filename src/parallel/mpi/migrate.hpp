// Parcel migration between the ranks of a block decomposition, over MPI (issue 6).
//
// After the drift, each rank sends every parcel whose position now lies in another rank's
// block straight to that rank, with the contact history it takes along (migration.hpp),
// and appends the parcels it receives. A parcel may cross a face, an edge or a corner of
// its block, but not go further than the 26 neighbouring blocks in one migration: a
// parcel moves far less than one block between two list builds (skin/2).
//
// Exchange: with each neighbour, one message of the buffer's size, then the buffer
// (non-blocking sends and receives, then wait for all), so a rank talks only to its
// neighbours, whatever the number of ranks.
//
// Errors (a parcel outside the box, or beyond the neighbouring blocks; stale lists; a bad
// buffer) are raised on every rank together: the rank that found one throws its message,
// the others throw an Error naming that rank, so that no rank is left waiting in a later
// collective call.
#pragma once
#include <mpi.h>

#include <cstdint>

#include "parallel/decomposition.hpp"
#include "parallel/migration.hpp"

namespace cgdem::parallel {

struct MigrationCounts {
  BufferCounts sent, received;  // this rank's parcels and histories, summed over neighbours
};

// Collective over comm, whose size must be d.ranks() (rank r owns d.block(r)).
//   reads   p.x, nl's lists (those of p: call it before nl.build(), after the drift)
//   writes  p (leavers removed, arrivals appended), nl (retain(), incoming)
// Afterwards every parcel of p lies in this rank's block; nl must be rebuilt
// (nl.build() attaches the carried histories).
MigrationCounts migrate(MPI_Comm comm, const Decomposition& d, Particles& p, NeighborList& nl);

// Totals over all ranks, to check that a migration loses and duplicates nothing.
struct ParcelTotals {
  int64_t count = 0;
  double mass = 0;          // sum of 1 / inv_mass [kg] (rounding depends on the order)
  uint64_t id_checksum = 0;  // sum of the ids modulo 2^64: exact, order-free
};
// Over the parcels 0..n-1 of each rank (all by default; with ghosts, pass the owned count).
ParcelTotals global_totals(MPI_Comm comm, const Particles& p, size_t n = SIZE_MAX);

}  // namespace cgdem::parallel
