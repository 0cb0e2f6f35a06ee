// Halo exchange of the air fields; see halo.hpp.
#include "parallel/mpi/halo.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"

namespace cgdem::air_mpi {

using fluid::Field;
using fluid::kGhost;

namespace {

// A box of indices [lo, hi) of a Field (ghost indices allowed).
struct Box {
  std::array<int, 3> lo, hi;
  long size() const { return long(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

// Visits the entries of a box in a fixed order (i fastest), with a running buffer position.
template <class Fn>
void for_box(Field& f, const Box& b, Fn fn) {
  long q = 0;
  for (int k = b.lo[2]; k < b.hi[2]; ++k)
    for (int j = b.lo[1]; j < b.hi[1]; ++j) {
      double* row = &f(0, j, k);
      for (int i = b.lo[0]; i < b.hi[0]; ++i) fn(row[i], q++);
    }
}

// The box of layers [first, last) along axis a, over the padded extent of the other axes.
Box layers(const Field& f, int a, int first, int last) {
  Box b;
  const auto e = f.extent();
  for (int d = 0; d < 3; ++d) b.lo[d] = -kGhost, b.hi[d] = e[d] + kGhost;
  b.lo[a] = first, b.hi[a] = last;
  return b;
}

// Message tags: one per axis and direction, so the two messages between a pair never mix.
int tag(int axis, bool upward) { return 40 + 2 * axis + (upward ? 1 : 0); }

}  // namespace

Halo::Halo(MPI_Comm comm, const GridBlocks& blocks) : comm_(comm), blocks_(blocks) {
  int size = 0, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  if (size != blocks.ranks() || rank != blocks.rank())
    throw Error(fmt::format("air halo: blocks for rank {} of {} used on rank {} of {}", blocks.rank(), blocks.ranks(),
                            rank, size));
}

void Halo::check_field(const Field& f, int stagger) const {
  if (stagger < kCellCentred || stagger > 2) throw Error(fmt::format("air halo: stagger axis {} is not -1, 0, 1 or 2", stagger));
  auto want = blocks_.local_cells();
  if (stagger >= 0) want[stagger] += 1;
  if (f.extent() != want)
    throw Error(fmt::format("air halo: field of {} x {} x {} entries, expected {} x {} x {} for this block{}", f.ni(),
                            f.nj(), f.nk(), want[0], want[1], want[2],
                            stagger >= 0 ? fmt::format(" (faces normal to {})", "xyz"[stagger]) : std::string()));
}

void Halo::exchange(Field& f, int stagger) {
  check_field(f, stagger);
  for (int a = 0; a < 3; ++a) sweep(f, stagger, a, false);
}

void Halo::reverse_add(Field& f, int stagger) {
  check_field(f, stagger);
  for (int a = 2; a >= 0; --a) sweep(f, stagger, a, true);
}

// One sweep along axis a. Forward: send the owned layers the neighbours hold as ghosts and
// overwrite the own ghosts. Reverse: send the ghosts to their owners, add what arrives into
// the owned layers (lower block's part first), zero the sent ghosts.
void Halo::sweep(Field& f, int stagger, int a, bool reverse) {
  const int lo_nb = blocks_.neighbour(2 * a), hi_nb = blocks_.neighbour(2 * a + 1);
  if (lo_nb < 0 && hi_nb < 0) return;
  const int n = blocks_.local_cells()[a];
  const int s = stagger == a ? 1 : 0;
  // Layers exchanged with each side: [0] towards/from the lower block, [1] the upper one.
  const Box own[2] = {layers(f, a, 0, kGhost + s), layers(f, a, n - kGhost, n)};
  const Box ghost[2] = {layers(f, a, -kGhost, 0), layers(f, a, n, n + kGhost + s)};
  const int nb[2] = {lo_nb, hi_nb};
  // Forward sends own[h] and receives into ghost[h]; reverse sends ghost[h], adds into own[h].
  MPI_Request req[4];
  int nreq = 0;
  for (int h = 0; h < 2; ++h) {
    if (nb[h] < 0) continue;
    const Box& in = reverse ? own[h] : ghost[h];
    recv_[h].resize(in.size());
    // What arrives from the lower block travels upward, and the other way round.
    MPI_Irecv(recv_[h].data(), int(recv_[h].size()), MPI_DOUBLE, nb[h], tag(a, h == 0), comm_, &req[nreq++]);
  }
  for (int h = 0; h < 2; ++h) {
    if (nb[h] < 0) continue;
    const Box& out = reverse ? ghost[h] : own[h];
    send_[h].resize(out.size());
    double* buf = send_[h].data();
    for_box(f, out, [buf](double& v, long q) { buf[q] = v; });
    MPI_Isend(send_[h].data(), int(send_[h].size()), MPI_DOUBLE, nb[h], tag(a, h == 1), comm_, &req[nreq++]);
  }
  MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
  for (int h = 0; h < 2; ++h) {
    if (nb[h] < 0) continue;
    const double* buf = recv_[h].data();
    if (reverse) {
      for_box(f, own[h], [buf](double& v, long q) { v += buf[q]; });
      for_box(f, ghost[h], [](double& v, long) { v = 0.0; });
    } else {
      for_box(f, ghost[h], [buf](double& v, long q) { v = buf[q]; });
    }
  }
}

fluid::FluidBoundary local_boundary(const GridBlocks& blocks, const fluid::FluidBoundary& global) {
  fluid::validate_boundary(global);
  fluid::FluidBoundary bc = global;
  for (int side = 0; side < 6; ++side) {
    if (global[side].type == fluid::BcType::Periodic)
      throw Error("air halo: periodic sides are not supported by the block exchange (it does not wrap)");
    if (blocks.is_cut(side)) bc[side] = fluid::SideBc{fluid::BcType::Open, {}, 0.0};
  }
  return bc;
}

void fill_scalar(Halo& halo, const fluid::MacGrid& local, const fluid::FluidBoundary& global_bc, Field& s,
                 fluid::ScalarKind kind) {
  fluid::fill_scalar_ghosts(local, local_boundary(halo.blocks(), global_bc), s, kind);
  halo.exchange(s, kCellCentred);
}

void fill_velocity(Halo& halo, const fluid::MacGrid& local, const fluid::FluidBoundary& global_bc, Field& u, Field& v,
                   Field& w) {
  fluid::fill_velocity_ghosts(local, local_boundary(halo.blocks(), global_bc), u, v, w);
  halo.exchange(u, 0);
  halo.exchange(v, 1);
  halo.exchange(w, 2);
}

}  // namespace cgdem::air_mpi
