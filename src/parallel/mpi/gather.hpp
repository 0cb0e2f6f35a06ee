// The ranks' DEM states brought together on one rank, and a gathered state handed out
// again (issue 6: output that reads as a serial run's, restart on another rank count).
#pragma once
#include <mpi.h>

#include "parallel/decomposition.hpp"
#include "parallel/portable_state.hpp"

namespace cgdem::parallel {

// Collective over comm. Every rank passes the state of its own parcels
// (portable_state() with its ghost count); `root` receives their union in increasing id
// (merge()), the other ranks an empty state. The bytes travel as one MPI_Gatherv; a rank
// whose state exceeds one MPI message (2^31 bytes), or a union that does, stops every
// rank with a message.
PortableState gather_state(MPI_Comm comm, const PortableState& local, int root = 0);

// Collective over comm: parcels [0, n_owned) of every rank (its own, not its ghosts), on
// `root` in increasing id, without histories (outputs); the other ranks get none.
Particles gather_particles(MPI_Comm comm, const Particles& p, size_t n_owned, int root = 0);
// The same with only id, species, x, v and radius filled (the other fields zero): a fifth
// of the bytes, for what reads only where the parcels are and how they move (the
// die-filling diagnostics, every 0.1 ms).
Particles gather_kinematics(MPI_Comm comm, const Particles& p, size_t n_owned, int root = 0);

// Collective over comm, whose size must be d.ranks(). `all` need only be filled on
// `root`: it is broadcast, and each rank appends the parcels of its block (d.owner_of)
// to p and queues their histories in nl.incoming (restore()); nl.build() comes next.
// Returns the parcels this rank took. This is how a checkpoint written on any number of
// ranks restarts on this one.
size_t scatter_state(MPI_Comm comm, const Decomposition& d, const PortableState& all, Particles& p, NeighborList& nl,
                     int root = 0);

}  // namespace cgdem::parallel
