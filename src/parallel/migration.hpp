// Parcels that leave a rank's block, packed with their contact history for their new
// owner, and unpacked there (issue 6). Serial: the MPI exchange is mpi/migrate.hpp.
//
// A parcel takes along
//   * every field of Particles (parcel_fields.hpp);
//   * the history of each of its pairs that is not empty, keyed by the two particle ids,
//     in the frame of the lower id: a pair is stored under its owner, the lower LOCAL
//     index, in the owner's frame, so pack_leaving() flips it when the owner has the
//     higher id, and NeighborList::build() on the receiving rank flips it back when its
//     own owner of the pair is the higher id;
//   * the history of each of its wall contacts that is not empty, keyed by (id, part).
// A pair whose two parcels go to different ranks is sent to both, and a pair of which one
// parcel leaves while the other stays is also queued in the staying side's
// NeighborList::incoming: the pair is then split across ranks, and each rank's build()
// attaches the record to the entry of its parcel and the partner's ghost
// (mpi/distributed_dem.hpp; without ghosts the build finds no such entry and drops it).
// Records already queued in nl.incoming (the split pairs of the last lists, by id) that
// name a leaving parcel travel with it as well: its pairs with other ranks' parcels.
//
// Buffer (one per destination, std::byte, native layout: all ranks run the same binary):
//   Header | each field of Particles in declaration order, n_parcels elements each
//          | n_pairs CarriedPair | n_walls CarriedWall
// Field-major, so that packing and unpacking a field are one loop or one memcpy.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "particles/neighbor_list.hpp"
#include "particles/particles.hpp"

namespace cgdem::parallel {

using Buffer = std::vector<std::byte>;

struct BufferCounts {
  int64_t parcels = 0, pairs = 0, walls = 0;
};

// Bytes of one parcel in a buffer: the sum of the element sizes of every Particles field.
size_t parcel_bytes();

// One buffer per destination d = 0..n_dest-1, holding the parcels i with dest[i] == d
// (in increasing i) and the histories they take along; dest[i] < 0: parcel i stays.
//   reads  p, nl (its lists must be those of p, or empty: no histories then;
//          nl.incoming: the queued pair and wall records that name a leaving parcel)
// Throws cgdem::Error when dest does not match p, names a destination out of range, or nl
// is stale.
std::vector<Buffer> pack_leaving(const Particles& p, const NeighborList& nl, std::span<const int> dest, int n_dest);

// The counts in a buffer's header; throws cgdem::Error when the buffer is not one that
// pack_leaving() wrote (wrong tag, record size or length).
BufferCounts read_counts(std::span<const std::byte> buffer);

// Appends the buffer's parcels to p (in packed order) and queues their histories in
// nl.incoming, for the next nl.build(). Leaves nl's lists alone: after a migration use
// apply_migration(), which keeps them in step with p. Returns the parcels appended.
size_t unpack_arriving(std::span<const std::byte> buffer, Particles& p, NeighborList& nl);

// One rank's side of a migration once the buffers have travelled: removes the parcels
// with dest[i] >= 0, appends those of `arrived`, and renumbers nl's history of the pairs
// and wall contacts among the parcels that stayed (NeighborList::retain), so that the
// next nl.build() carries it over together with the arrived histories. The history of a
// pair with one parcel leaving and one staying is queued in nl.incoming (by id, for the
// ghost entry of the next build). Every buffer is checked before anything changes.
// Returns the parcels appended.
size_t apply_migration(Particles& p, NeighborList& nl, std::span<const int> dest, std::span<const Buffer> arrived);

// Copies of the parcels `members` of p (every field, in the order given), without
// histories: the ghost parcels a rank sends a neighbour at each list build. Read with
// unpack_arriving().
Buffer pack_copies(const Particles& p, std::span<const int> members);

}  // namespace cgdem::parallel
