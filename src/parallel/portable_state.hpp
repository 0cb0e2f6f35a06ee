// The DEM state in a form that does not depend on local indices or on the rank layout
// (issue 6, items 4 and 5 of docs/scale_out.md): every parcel in increasing id, and the
// contact histories keyed by particle ids (the CarriedPair / CarriedWall records of the
// migration buffers). It is what the ranks gather for output and checkpoints, and what a
// run on any number of ranks restarts from: each rank takes the parcels of its block and
// queues their histories in NeighborList::incoming, which the next build() attaches.
//
// A run on several ranks holds a pair split by a cut on both ranks (the owned parcel and a
// ghost copy of the other). So that the union over the ranks holds each pair once,
// portable_state() records a pair with a ghost only on the rank that owns its parcel of
// lower id; a pair of two owned parcels is recorded where they are.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "io/archive.hpp"
#include "particles/neighbor_list.hpp"
#include "particles/particles.hpp"

namespace cgdem::parallel {

struct PortableState {
  Particles p;                     // increasing id
  std::vector<CarriedPair> pairs;  // non-empty histories, id_a < id_b, id_a's frame; sorted by (id_a, id_b)
  std::vector<CarriedWall> walls;  // non-empty histories, parcel's frame; sorted by (id, part)
  size_t size() const { return p.size(); }
};

// The state of parcels [0, n_owned) of p; the parcels after them are ghosts (copies of
// other ranks' parcels), which are left out, and so are their own pairs and wall contacts.
// nl must be the lists of p (or empty: no histories). Histories still queued in
// nl.incoming (a migration since the last build) are included for the owned parcels.
//   reads  p, nl;  throws cgdem::Error when nl is stale or n_owned > p.size()
PortableState portable_state(const Particles& p, const NeighborList& nl, size_t n_owned);
inline PortableState portable_state(const Particles& p, const NeighborList& nl) {
  return portable_state(p, nl, p.size());
}

// The union of the states of disjoint sets of parcels (one per rank), in the same order
// as one state of all of them. Throws cgdem::Error naming an id held by two parts, or a
// pair recorded twice.
PortableState merge(std::vector<PortableState> parts);

// Appends to p, in increasing id, the parcels of s whose position satisfies `mine`, and
// queues in nl.incoming every history that involves one of them (a pair whose other
// parcel is elsewhere is kept too: it attaches to the ghost entry of a run with ghosts,
// and is dropped by build() otherwise). Call nl.build() next. Returns the parcels taken.
size_t restore(const PortableState& s, const std::function<bool(const Vec3&)>& mine, Particles& p,
               NeighborList& nl);

// Archive form (checkpoints, and the bytes the ranks gather): every Particles field
// (for_each_field), then the records. load() checks the order and the sizes.
void save(io::ArchiveWriter& w, const PortableState& s);
void load(io::ArchiveReader& r, PortableState& s);

}  // namespace cgdem::parallel
