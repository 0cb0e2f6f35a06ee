#include "parallel/mpi/field_gather.hpp"

#include <fmt/format.h>

#include <climits>
#include <vector>

#include "core/error.hpp"

namespace cgdem::air_mpi {

namespace {

// The owned box of block `coords` in global indices [lo, hi) of the field with this
// stagger, and the block's local extent.
struct Owned {
  std::array<int, 3> lo, hi, extent;
};

Owned owned_of(const GridBlocks& b, const Dims& coords, int stagger) {
  Owned o;
  for (int a = 0; a < 3; ++a) {
    o.lo[a] = b.run_start(a, coords[a]);
    o.hi[a] = b.run_start(a, coords[a] + 1);
    o.extent[a] = o.hi[a] - o.lo[a] + (a == stagger ? 1 : 0);
    if (a == stagger && coords[a] == b.dims()[a] - 1) ++o.hi[a];  // the domain's upper face
  }
  return o;
}

long count(const Owned& o) {
  return static_cast<long>(o.hi[0] - o.lo[0]) * (o.hi[1] - o.lo[1]) * (o.hi[2] - o.lo[2]);
}

void check_mpi(int rc, const char* call) {
  if (rc != MPI_SUCCESS) throw Error(fmt::format("air field gather: {} failed", call));
}

// Every rank's owned entry count and its offset in the gathered buffer (rank order).
void layout(const GridBlocks& b, int stagger, std::vector<int>& counts, std::vector<int>& displs) {
  counts.assign(b.ranks(), 0);
  displs.assign(b.ranks(), 0);
  long total = 0;
  for (int r = 0; r < b.ranks(); ++r) {
    const Dims c{r % b.dims()[0], (r / b.dims()[0]) % b.dims()[1], r / (b.dims()[0] * b.dims()[1])};
    const long n = count(owned_of(b, c, stagger));
    if (total + n > INT_MAX) throw Error("air field gather: more than 2^31 entries in one message");
    counts[r] = static_cast<int>(n);
    displs[r] = static_cast<int>(total);
    total += n;
  }
}

std::array<int, 3> global_extent(const GridBlocks& b, int stagger) {
  std::array<int, 3> e = b.global_cells();
  if (stagger >= 0) ++e[stagger];
  return e;
}

// Copies the owned box between a block-local field (offset lo) and a packed buffer.
template <class Visit>
void for_owned(const Owned& o, Visit&& visit) {
  long k = 0;
  for (int z = o.lo[2]; z < o.hi[2]; ++z)
    for (int y = o.lo[1]; y < o.hi[1]; ++y)
      for (int x = o.lo[0]; x < o.hi[0]; ++x) visit(x, y, z, k++);
}

}  // namespace

fluid::Field gather_field(MPI_Comm comm, const GridBlocks& b, const fluid::Field& local, int stagger, int root) {
  const Owned mine = owned_of(b, b.coords(), stagger);
  if (local.extent() != mine.extent)
    throw Error(fmt::format("air field gather: a field of {} x {} x {} entries on a block of {} x {} x {}",
                            local.ni(), local.nj(), local.nk(), mine.extent[0], mine.extent[1], mine.extent[2]));
  std::vector<double> send(count(mine));
  for_owned(mine, [&](int x, int y, int z, long k) { send[k] = local(x - mine.lo[0], y - mine.lo[1], z - mine.lo[2]); });
  std::vector<int> counts, displs;
  layout(b, stagger, counts, displs);
  const bool at_root = b.rank() == root;
  std::vector<double> all(at_root ? static_cast<size_t>(displs.back()) + counts.back() : 0);
  check_mpi(MPI_Gatherv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, all.data(), counts.data(),
                        displs.data(), MPI_DOUBLE, root, comm),
            "MPI_Gatherv");
  if (!at_root) return {};
  fluid::Field g(global_extent(b, stagger));
  for (int r = 0; r < b.ranks(); ++r) {
    const Dims c{r % b.dims()[0], (r / b.dims()[0]) % b.dims()[1], r / (b.dims()[0] * b.dims()[1])};
    const double* from = all.data() + displs[r];
    for_owned(owned_of(b, c, stagger), [&](int x, int y, int z, long k) { g(x, y, z) = from[k]; });
  }
  return g;
}

void scatter_field(MPI_Comm comm, const GridBlocks& b, const fluid::Field& global, fluid::Field& local, int stagger,
                   int root) {
  const bool at_root = b.rank() == root;
  if (at_root && global.extent() != global_extent(b, stagger))
    throw Error(fmt::format("air field scatter: a global field of {} x {} x {} entries for a grid of {} x {} x {} cells",
                            global.ni(), global.nj(), global.nk(), b.global_cells()[0], b.global_cells()[1],
                            b.global_cells()[2]));
  std::vector<int> counts, displs;
  layout(b, stagger, counts, displs);
  std::vector<double> all;
  if (at_root) {
    all.resize(static_cast<size_t>(displs.back()) + counts.back());
    for (int r = 0; r < b.ranks(); ++r) {
      const Dims c{r % b.dims()[0], (r / b.dims()[0]) % b.dims()[1], r / (b.dims()[0] * b.dims()[1])};
      double* to = all.data() + displs[r];
      for_owned(owned_of(b, c, stagger), [&](int x, int y, int z, long k) { to[k] = global(x, y, z); });
    }
  }
  const Owned mine = owned_of(b, b.coords(), stagger);
  std::vector<double> recv(count(mine));
  check_mpi(MPI_Scatterv(all.data(), counts.data(), displs.data(), MPI_DOUBLE, recv.data(),
                         static_cast<int>(recv.size()), MPI_DOUBLE, root, comm),
            "MPI_Scatterv");
  local = fluid::Field(mine.extent);
  for_owned(mine, [&](int x, int y, int z, long k) { local(x - mine.lo[0], y - mine.lo[1], z - mine.lo[2]) = recv[k]; });
}

}  // namespace cgdem::air_mpi
