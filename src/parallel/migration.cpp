#include "parallel/migration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <type_traits>

#include "core/error.hpp"
#include "parallel/parcel_fields.hpp"

namespace cgdem::parallel {

namespace {

// The records go through memcpy: no pointers, no padding (uninitialised padding bytes
// would make equal buffers differ).
static_assert(std::is_trivially_copyable_v<contact::History> && sizeof(contact::History) == 8 * sizeof(double));
static_assert(std::is_trivially_copyable_v<CarriedPair> &&
              sizeof(CarriedPair) == 2 * sizeof(int64_t) + sizeof(contact::History));
static_assert(std::is_trivially_copyable_v<CarriedWall> &&
              sizeof(CarriedWall) == 2 * sizeof(int64_t) + sizeof(contact::History));

constexpr uint64_t kTag = 0x31'6b'63'61'70'64'67'63;  // "cgdpack1" in memory order

struct Header {
  uint64_t tag;
  int64_t parcel_bytes;  // catches a buffer from a build with other Particles fields
  BufferCounts n;
};
static_assert(std::is_trivially_copyable_v<Header> && sizeof(Header) == 5 * sizeof(int64_t));

template <class T>
using ElementOf = typename std::remove_cvref_t<T>::value_type;

size_t payload_bytes(const BufferCounts& n) {
  return n.parcels * parcel_bytes() + n.pairs * sizeof(CarriedPair) + n.walls * sizeof(CarriedWall);
}

template <class T>
void append(Buffer& b, const T* src, size_t count) {
  const size_t at = b.size();
  b.resize(at + count * sizeof(T));
  if (count) std::memcpy(b.data() + at, src, count * sizeof(T));
}

// Appends `count` records of the buffer at `at` to v and advances `at`.
template <class T>
void take(std::span<const std::byte> b, size_t& at, size_t count, std::vector<T>& v) {
  const size_t old = v.size();
  v.resize(old + count);
  if (count) std::memcpy(v.data() + old, b.data() + at, count * sizeof(T));
  at += count * sizeof(T);
}

Buffer serialise(const Particles& p, std::span<const int> members, const std::vector<CarriedPair>& pairs,
                 const std::vector<CarriedWall>& walls) {
  const Header h{kTag, static_cast<int64_t>(parcel_bytes()),
                 {static_cast<int64_t>(members.size()), static_cast<int64_t>(pairs.size()),
                  static_cast<int64_t>(walls.size())}};
  Buffer b;
  b.reserve(sizeof(Header) + payload_bytes(h.n));
  append(b, &h, 1);
  for_each_field(p, [&](const auto& field) {
    using T = ElementOf<decltype(field)>;
    static_assert(std::is_trivially_copyable_v<T>, "a Particles field must be trivially copyable to migrate");
    std::vector<T> column(members.size());
    for (size_t k = 0; k < members.size(); ++k) column[k] = field[members[k]];
    append(b, column.data(), column.size());
  });
  append(b, pairs.data(), pairs.size());
  append(b, walls.data(), walls.size());
  return b;
}

// The record of pair (i, j), whose history h is in i's frame, in the lower id's frame.
CarriedPair carried(const Particles& p, int i, int j, const contact::History& h) {
  return p.id[i] < p.id[j] ? CarriedPair{p.id[i], p.id[j], h} : CarriedPair{p.id[j], p.id[i], h.flipped()};
}

void check_lists(const Particles& p, const NeighborList& nl, const char* what) {
  if (!nl.offset.empty() && !nl.valid_for(p))
    throw Error(fmt::format("{}: the neighbour lists hold {} particles, the particles {}; build the lists first",
                            what, nl.offset.size() - 1, p.size()));
}

}  // namespace

size_t parcel_bytes() {
  size_t n = 0;
  Particles none;
  for_each_field(none, [&](const auto& field) { n += sizeof(ElementOf<decltype(field)>); });
  return n;
}

std::vector<Buffer> pack_leaving(const Particles& p, const NeighborList& nl, std::span<const int> dest, int n_dest) {
  if (dest.size() != p.size())
    throw Error(fmt::format("migration: {} destinations for {} parcels", dest.size(), p.size()));
  check_lists(p, nl, "migration");
  std::vector<std::vector<int>> members(n_dest);
  for (size_t i = 0; i < dest.size(); ++i) {
    if (dest[i] >= n_dest)
      throw Error(fmt::format("migration: parcel id {} is sent to destination {}, but there are {}", p.id[i], dest[i],
                              n_dest));
    if (dest[i] >= 0) members[dest[i]].push_back(static_cast<int>(i));
  }
  std::vector<std::vector<CarriedPair>> pairs(n_dest);
  std::vector<std::vector<CarriedWall>> walls(n_dest);
  const int np = nl.offset.empty() ? 0 : static_cast<int>(p.size());
  for (int i = 0; i < np; ++i) {
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int j = nl.partner[e];
      if ((dest[i] < 0 && dest[j] < 0) || nl.hist.empty(e)) continue;
      const CarriedPair c = carried(p, i, j, nl.hist.get(e));  // the record is in the frame of i, the owner
      if (dest[i] >= 0) pairs[dest[i]].push_back(c);
      if (dest[j] >= 0 && dest[j] != dest[i]) pairs[dest[j]].push_back(c);
    }
    if (dest[i] < 0) continue;
    for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
      if (!nl.wall_hist[e].empty()) walls[dest[i]].push_back({p.id[i], nl.wall_part[e], nl.wall_hist[e]});
  }
  // Queued records that name a leaving parcel go with it (once per destination).
  if (!nl.incoming.empty()) {
    std::vector<std::pair<int64_t, int>> leaving;  // (id, destination), sorted by id
    for (size_t i = 0; i < dest.size(); ++i)
      if (dest[i] >= 0) leaving.emplace_back(p.id[i], dest[i]);
    std::sort(leaving.begin(), leaving.end());
    auto dest_of = [&leaving](int64_t id) {
      const auto it = std::lower_bound(leaving.begin(), leaving.end(), std::pair<int64_t, int>{id, INT_MIN});
      return it != leaving.end() && it->first == id ? it->second : -1;
    };
    for (const CarriedPair& c : nl.incoming.pairs) {
      const int da = dest_of(c.id_a), db = dest_of(c.id_b);
      if (da >= 0) pairs[da].push_back(c);
      if (db >= 0 && db != da) pairs[db].push_back(c);
    }
    for (const CarriedWall& c : nl.incoming.walls)
      if (const int dw = dest_of(c.id); dw >= 0) walls[dw].push_back(c);
  }
  std::vector<Buffer> out(n_dest);
  for (int d = 0; d < n_dest; ++d) out[d] = serialise(p, members[d], pairs[d], walls[d]);
  return out;
}

BufferCounts read_counts(std::span<const std::byte> buffer) {
  Header h;
  if (buffer.size() < sizeof(Header))
    throw Error(fmt::format("migration buffer of {} bytes is shorter than its header ({} bytes)", buffer.size(),
                            sizeof(Header)));
  std::memcpy(&h, buffer.data(), sizeof(Header));
  if (h.tag != kTag) throw Error("migration buffer: wrong tag (not written by pack_leaving)");
  if (h.parcel_bytes != static_cast<int64_t>(parcel_bytes()))
    throw Error(fmt::format("migration buffer: parcels of {} bytes, this build's are {} (Particles fields differ)",
                            h.parcel_bytes, parcel_bytes()));
  const size_t room = buffer.size() - sizeof(Header);
  const bool fits = h.n.parcels >= 0 && h.n.pairs >= 0 && h.n.walls >= 0 &&
                    static_cast<uint64_t>(h.n.parcels) <= room / parcel_bytes() &&
                    static_cast<uint64_t>(h.n.pairs) <= room / sizeof(CarriedPair) &&
                    static_cast<uint64_t>(h.n.walls) <= room / sizeof(CarriedWall);  // no overflow below
  if (!fits || room != payload_bytes(h.n))
    throw Error(fmt::format("migration buffer: {} bytes after its header, which announces {} parcels ({} bytes each), "
                            "{} pair and {} wall histories ({} bytes each)",
                            room, h.n.parcels, parcel_bytes(), h.n.pairs, h.n.walls, sizeof(CarriedPair)));
  return h.n;
}

size_t unpack_arriving(std::span<const std::byte> buffer, Particles& p, NeighborList& nl) {
  const BufferCounts n = read_counts(buffer);
  size_t at = sizeof(Header);
  for_each_field(p, [&](auto& field) { take(buffer, at, n.parcels, field); });
  take(buffer, at, n.pairs, nl.incoming.pairs);
  take(buffer, at, n.walls, nl.incoming.walls);
  return n.parcels;
}

size_t apply_migration(Particles& p, NeighborList& nl, std::span<const int> dest, std::span<const Buffer> arrived) {
  if (dest.size() != p.size())
    throw Error(fmt::format("migration: {} destinations for {} parcels", dest.size(), p.size()));
  check_lists(p, nl, "migration");
  for (const Buffer& b : arrived) read_counts(b);
  // Pairs that the migration splits: the staying side keeps the history too, by id.
  const int np = nl.offset.empty() ? 0 : static_cast<int>(p.size());
  for (int i = 0; i < np; ++i)
    for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const int j = nl.partner[e];
      if ((dest[i] < 0) == (dest[j] < 0) || nl.hist.empty(e)) continue;
      nl.incoming.pairs.push_back(carried(p, i, j, nl.hist.get(e)));
    }
  std::vector<int> keep;
  keep.reserve(p.size());
  for (size_t i = 0; i < dest.size(); ++i)
    if (dest[i] < 0) keep.push_back(static_cast<int>(i));
  p.reorder(keep);
  size_t n_arrived = 0;
  for (const Buffer& b : arrived) n_arrived += unpack_arriving(b, p, nl);
  nl.retain(keep, n_arrived);
  return n_arrived;
}

Buffer pack_copies(const Particles& p, std::span<const int> members) {
  for (const int i : members)
    if (i < 0 || static_cast<size_t>(i) >= p.size())
      throw Error(fmt::format("ghost copies: parcel {} of {}", i, p.size()));
  return serialise(p, members, {}, {});
}

}  // namespace cgdem::parallel
