#include "parallel/mpi/migrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <string>

#include "core/error.hpp"
#include "parallel/mpi/exchange.hpp"

namespace cgdem::parallel {

namespace {

constexpr int kSizeTag = 6101, kBufferTag = 6102;
constexpr const char* kWhat = "migration";

void check(int rc, const char* call) { check_mpi(rc, call, kWhat); }

// The neighbour slot of each parcel that leaves (-1: it stays), or the first error found.
std::string destinations(const Decomposition& d, int rank, const std::vector<int>& nb, const Particles& p,
                         std::vector<int>& dest) {
  dest.assign(p.size(), -1);
  const geometry::Aabb& box = d.box();
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.x[i];
    if (!d.contains(x))
      return fmt::format("migration: parcel id {} at ({:.9g}, {:.9g}, {:.9g}) m on rank {} is outside the decomposed "
                         "box [{:g}, {:g}] x [{:g}, {:g}] x [{:g}, {:g}] m (escaped parcels must be removed first)",
                         p.id[i], x.x, x.y, x.z, rank, box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
    const int owner = d.owner_of(x);
    if (owner == rank) continue;
    const auto it = std::lower_bound(nb.begin(), nb.end(), owner);
    if (it == nb.end() || *it != owner)
      return fmt::format("migration: parcel id {} at ({:.9g}, {:.9g}, {:.9g}) m moved from the block of rank {} to "
                         "that of rank {}, which is not a neighbour: it travelled more than one block since the last "
                         "migration",
                         p.id[i], x.x, x.y, x.z, rank, owner);
    dest[i] = static_cast<int>(it - nb.begin());
  }
  return {};
}

void add(BufferCounts& sum, const BufferCounts& n) {
  sum.parcels += n.parcels;
  sum.pairs += n.pairs;
  sum.walls += n.walls;
}

}  // namespace

MigrationCounts migrate(MPI_Comm comm, const Decomposition& d, Particles& p, NeighborList& nl) {
  int rank = 0, size = 0;
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  if (size != d.ranks())  // the same on every rank: no need to raise it together
    throw Error(fmt::format("migration: {} ranks run a decomposition into {} x {} x {} = {} blocks", size, d.dims()[0],
                            d.dims()[1], d.dims()[2], d.ranks()));

  // 1. Where each parcel goes, and its buffer (raised together: the exchange needs all).
  const std::vector<int> nb = d.neighbours(rank);
  const int n = static_cast<int>(nb.size());
  std::vector<int> dest;
  std::vector<Buffer> out;
  std::string error = destinations(d, rank, nb, p, dest);
  if (error.empty()) {
    try {
      out = pack_leaving(p, nl, dest, n);
    } catch (const Error& e) {
      error = e.what();
    }
  }
  if (error.empty()) error = oversized(out, nb, kWhat);
  raise_together(comm, rank, error, kWhat);

  // 2. Sizes, then buffers, with each neighbour (every neighbour sends one of each, even empty).
  const std::vector<Buffer> in = exchange_buffers(comm, nb, out, kSizeTag, kBufferTag, kWhat);

  // 3. Leavers out, arrivals in, the lists renumbered for the next build.
  MigrationCounts c;
  try {
    for (int k = 0; k < n; ++k) {
      add(c.sent, read_counts(out[k]));
      add(c.received, read_counts(in[k]));
    }
    apply_migration(p, nl, dest, in);
  } catch (const Error& e) {
    error = e.what();
  }
  raise_together(comm, rank, error, kWhat);
  return c;
}

ParcelTotals global_totals(MPI_Comm comm, const Particles& p, size_t n) {
  ParcelTotals mine, all;
  n = std::min(n, p.size());
  mine.count = static_cast<int64_t>(n);
  for (size_t i = 0; i < n; ++i) {
    mine.mass += 1.0 / p.inv_mass[i];
    mine.id_checksum += static_cast<uint64_t>(p.id[i]);
  }
  check(MPI_Allreduce(&mine.count, &all.count, 1, MPI_INT64_T, MPI_SUM, comm), "MPI_Allreduce");
  check(MPI_Allreduce(&mine.mass, &all.mass, 1, MPI_DOUBLE, MPI_SUM, comm), "MPI_Allreduce");
  check(MPI_Allreduce(&mine.id_checksum, &all.id_checksum, 1, MPI_UINT64_T, MPI_SUM, comm), "MPI_Allreduce");
  return all;
}

}  // namespace cgdem::parallel
