#include "parallel/mpi/gather.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <type_traits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "parallel/mpi/exchange.hpp"

namespace cgdem::parallel {

namespace {

constexpr const char* kGather = "gather of the parcels";
constexpr const char* kScatter = "hand-out of the parcels";

std::string bytes_of(const PortableState& s) {
  io::ArchiveWriter w;
  save(w, s);
  return w.bytes();
}

PortableState state_of(std::string bytes, const std::string& name) {
  io::ArchiveReader r(std::move(bytes), name);
  PortableState s;
  load(r, s);
  return s;
}

}  // namespace

PortableState gather_state(MPI_Comm comm, const PortableState& local, int root) {
  int rank = 0, size = 0;
  check_mpi(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank", kGather);
  check_mpi(MPI_Comm_size(comm, &size), "MPI_Comm_size", kGather);
  const std::string mine = bytes_of(local);
  raise_together(comm, rank,
                 mine.size() > static_cast<size_t>(INT_MAX)
                     ? fmt::format("{}: rank {} holds {} bytes, more than one MPI message", kGather, rank, mine.size())
                     : std::string(),
                 kGather);
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(rank == root ? size : 0), displs;
  check_mpi(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm), "MPI_Gather", kGather);
  std::string error;
  long long total = 0;
  if (rank == root) {
    displs.resize(size);
    for (int r = 0; r < size; ++r) displs[r] = static_cast<int>(total), total += counts[r];
    if (total > INT_MAX) error = fmt::format("{}: {} bytes in all, more than one MPI message", kGather, total);
  }
  raise_together(comm, rank, error, kGather);
  std::string all(rank == root ? static_cast<size_t>(total) : 0, '\0');
  check_mpi(MPI_Gatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, root, comm),
            "MPI_Gatherv", kGather);
  if (rank != root) return {};
  std::vector<PortableState> parts(size);
  for (int r = 0; r < size; ++r)
    parts[r] = state_of(all.substr(displs[r], counts[r]), fmt::format("parcels of rank {}", r));
  return merge(std::move(parts));
}

Particles gather_particles(MPI_Comm comm, const Particles& p, size_t n_owned, int root) {
  return gather_state(comm, portable_state(p, NeighborList{}, n_owned), root).p;
}

namespace {

// One parcel's kinematics in a gather buffer (no padding: every byte is written).
struct Kinematics {
  int64_t id;
  int64_t species;
  Vec3 x, v;
  double radius;
};
static_assert(std::is_trivially_copyable_v<Kinematics> && sizeof(Kinematics) == 9 * 8);

}  // namespace

Particles gather_kinematics(MPI_Comm comm, const Particles& p, size_t n_owned, int root) {
  int rank = 0, size = 0;
  check_mpi(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank", kGather);
  check_mpi(MPI_Comm_size(comm, &size), "MPI_Comm_size", kGather);
  const size_t n = std::min(n_owned, p.size());
  std::vector<Kinematics> mine(n);
  for (size_t i = 0; i < n; ++i) mine[i] = {p.id[i], p.species[i], p.x[i], p.v[i], p.radius[i]};
  const long long bytes = static_cast<long long>(n * sizeof(Kinematics));
  raise_together(comm, rank,
                 bytes > INT_MAX ? fmt::format("{}: rank {} holds {} bytes, more than one MPI message", kGather, rank,
                                               bytes)
                                 : std::string(),
                 kGather);
  const int nb = static_cast<int>(bytes);
  std::vector<int> counts(rank == root ? size : 0), displs(rank == root ? size : 0);
  check_mpi(MPI_Gather(&nb, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm), "MPI_Gather", kGather);
  long long total = 0;
  for (int r = 0; r < static_cast<int>(counts.size()); ++r) displs[r] = static_cast<int>(total), total += counts[r];
  raise_together(comm, rank,
                 total > INT_MAX ? fmt::format("{}: {} bytes in all, more than one MPI message", kGather, total)
                                 : std::string(),
                 kGather);
  std::vector<Kinematics> all(static_cast<size_t>(total) / sizeof(Kinematics));
  check_mpi(MPI_Gatherv(mine.data(), nb, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, root, comm),
            "MPI_Gatherv", kGather);
  Particles out;
  if (rank != root) return out;
  std::sort(all.begin(), all.end(), [](const Kinematics& a, const Kinematics& b) { return a.id < b.id; });
  for_each_field(out, [&](auto& field) { field.resize(all.size()); });  // zeros
  for (size_t i = 0; i < all.size(); ++i) {
    out.id[i] = all[i].id;
    out.species[i] = static_cast<int>(all[i].species);
    out.x[i] = all[i].x;
    out.v[i] = all[i].v;
    out.radius[i] = all[i].radius;
  }
  return out;
}

size_t scatter_state(MPI_Comm comm, const Decomposition& d, const PortableState& all, Particles& p, NeighborList& nl,
                     int root) {
  int rank = 0, size = 0;
  check_mpi(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank", kScatter);
  check_mpi(MPI_Comm_size(comm, &size), "MPI_Comm_size", kScatter);
  if (size != d.ranks())
    throw Error(fmt::format("{}: {} ranks run a decomposition into {} blocks", kScatter, size, d.ranks()));
  std::string bytes = rank == root ? bytes_of(all) : std::string();
  std::string error;
  if (rank == root) {
    if (bytes.size() > static_cast<size_t>(INT_MAX))
      error = fmt::format("{}: {} bytes, more than one MPI message", kScatter, bytes.size());
    for (size_t i = 0; i < all.p.size() && error.empty(); ++i)
      if (!d.contains(all.p.x[i]))
        error = fmt::format("{}: parcel id {} at ({:.9g}, {:.9g}, {:.9g}) m is outside the decomposed box", kScatter,
                            all.p.id[i], all.p.x[i].x, all.p.x[i].y, all.p.x[i].z);
  }
  raise_together(comm, rank, error, kScatter);
  long long n = static_cast<long long>(bytes.size());
  check_mpi(MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm), "MPI_Bcast", kScatter);
  bytes.resize(static_cast<size_t>(n));
  check_mpi(MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, root, comm), "MPI_Bcast", kScatter);
  const PortableState s = rank == root ? PortableState{} : state_of(std::move(bytes), "broadcast parcels");
  const PortableState& use = rank == root ? all : s;
  return restore(use, [&](const Vec3& x) { return d.owner_of(x) == rank; }, p, nl);
}

}  // namespace cgdem::parallel
