// The distributed 7-point operator; see dist_poisson.hpp.
#include "solvers/pressure_mpi/dist_poisson.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "solvers/pressure/union_find.hpp"

namespace cgdem::air_mpi {

using pressure::Boundary;
using pressure::find_root;
using pressure::unite;

namespace {

constexpr int kTagCoef = 60, kTagLayer = 70, kTagLabel = 80;

// Sizes of the local face arrays and of the cell layer next to each side.
long face_count(const std::array<int, 3>& e, int axis) {
  std::array<long, 3> f{e[0], e[1], e[2]};
  f[axis] += 1;
  return f[0] * f[1] * f[2];
}
long layer_count(const std::array<int, 3>& e, int axis) {
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  return long(e[b]) * e[c];
}

// Calls fn(q, cell) for the cells of the layer next to side s, q = running index of the layer
// in the order (i, j, k) with i fastest among the two remaining axes.
template <class Fn>
void for_layer(const std::array<int, 3>& e, int side, Fn fn) {
  const int a = side / 2;
  const int at = side % 2 ? e[a] - 1 : 0;
  long q = 0;
  std::array<int, 3> lo{0, 0, 0}, hi = e;
  lo[a] = at, hi[a] = at + 1;
  for (int k = lo[2]; k < hi[2]; ++k)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int i = lo[0]; i < hi[0]; ++i) fn(q++, i + long(e[0]) * (j + long(e[1]) * k));
}

// The face (local MAC index) of side s next to a cell of that side's layer.
long side_face(const std::array<int, 3>& e, int side, long cell) {
  const int a = side / 2;
  long i = cell % e[0], j = (cell / e[0]) % e[1], k = cell / (long(e[0]) * e[1]);
  std::array<long, 3> c{i, j, k}, f{e[0], e[1], e[2]};
  f[a] += 1;
  if (side % 2) c[a] += 1;
  return c[0] + f[0] * (c[1] + f[1] * c[2]);
}

// Why the face coefficient arrays of set() are refused (a size other than the block's faces,
// a value negative or not finite), or "" when they are fine.
std::string coefficient_error(const std::array<int, 3>& e, const std::vector<double>* const (&in)[3]) {
  std::string why;
  for (int a = 0; a < 3; ++a) {
    if (long(in[a]->size()) != face_count(e, a))
      return fmt::format("face coefficient array a{} has {} entries, expected {}", "xyz"[a], in[a]->size(),
                         face_count(e, a));
    for (double v : *in[a])
      if (!(v >= 0.0) || !std::isfinite(v)) why = fmt::format("face coefficient a{} must be finite and >= 0", "xyz"[a]);
  }
  return why;
}

// The steps of DistPoisson::label_components (see dist_poisson.hpp).

// Step 1: the components of a block through its own faces with w > 0 (union-find, the
// smallest cell of a component its root).
struct BlockComponents {
  std::vector<long> root;     // per cell: the root of its component
  std::vector<char> grounded;  // per root: a cell of the component has an Open face
  std::vector<char> at_cut;    // per root: the component reaches a cut by a face with w > 0 (step 2)
  std::vector<double> count;   // per root: the component's cells
};

BlockComponents block_components(const std::array<int, 3>& e, const std::vector<double> (&w)[3],
                                 const std::vector<double>& open) {
  const int nx = e[0], ny = e[1], nz = e[2];
  const long n = long(nx) * ny * nz;
  std::vector<long> parent(n);
  std::iota(parent.begin(), parent.end(), 0L);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long c = i + long(nx) * (j + long(ny) * k);
        if (i > 0 && w[0][i + long(nx + 1) * (j + long(ny) * k)] > 0) unite(parent, c, c - 1);
        if (j > 0 && w[1][i + long(nx) * (j + long(ny + 1) * k)] > 0) unite(parent, c, c - nx);
        if (k > 0 && w[2][c] > 0) unite(parent, c, c - long(nx) * ny);
      }
  BlockComponents b;
  b.root.resize(n);
  for (long c = 0; c < n; ++c) b.root[c] = find_root(parent, c);
  b.grounded.assign(n, 0);
  b.at_cut.assign(n, 0);
  b.count.assign(n, 0.0);
  for (long c = 0; c < n; ++c) {
    if (open[c] > 0) b.grounded[b.root[c]] = 1;
    b.count[b.root[c]] += 1;
  }
  return b;
}

// Global id of a local cell: the global index of the cell (unique over the ranks, exact in
// a double for any grid this code can hold).
struct GlobalIds {
  std::array<int, 3> e, lo, gn;
  long operator()(long c) const {
    const long i = c % e[0], j = (c / e[0]) % e[1], k = c / (long(e[0]) * e[1]);
    return (lo[0] + i) + long(gn[0]) * ((lo[1] + j) + long(gn[1]) * (lo[2] + k));
  }
};

// Step 2: the labels (root ids) of the cells next to each cut, exchanged with the neighbours;
// marks b.at_cut for the roots joined to a cut through a face with w > 0 and returns the
// pairs (own root id, neighbour's root id) of those faces on the upper sides.
std::vector<long> cut_edges(MPI_Comm comm, const GridBlocks& blocks, const std::array<int, 3>& e,
                            const std::vector<double> (&wf)[3], const GlobalIds& gid, BlockComponents& b) {
  std::vector<long> edges;
  std::vector<double> out[6], in[6];
  MPI_Request rq[12];
  int nr = 0;
  for (int s = 0; s < 6; ++s) {
    const int nb = blocks.neighbour(s);
    if (nb < 0) continue;
    in[s].resize(layer_count(e, s / 2));
    MPI_Irecv(in[s].data(), int(in[s].size()), MPI_DOUBLE, nb, kTagLabel + (s ^ 1), comm, &rq[nr++]);
    out[s].resize(in[s].size());
    for_layer(e, s, [&](long q, long c) { out[s][q] = double(gid(b.root[c])); });
    MPI_Isend(out[s].data(), int(out[s].size()), MPI_DOUBLE, nb, kTagLabel + s, comm, &rq[nr++]);
  }
  MPI_Waitall(nr, rq, MPI_STATUSES_IGNORE);
  for (int s = 0; s < 6; ++s) {
    if (!blocks.is_cut(s)) continue;
    const double* w = wf[s / 2].data();
    for_layer(e, s, [&](long q, long c) {
      if (!(w[side_face(e, s, c)] > 0)) return;
      b.at_cut[b.root[c]] = 1;
      if (s % 2) edges.insert(edges.end(), {gid(b.root[c]), long(in[s][q])});
    });
  }
  return edges;
}

// Every rank's `mine`, concatenated in rank order, on every rank.
std::vector<long> gather_all(MPI_Comm comm, const std::vector<long>& mine) {
  int size = 0;
  MPI_Comm_size(comm, &size);
  int m = int(mine.size());
  std::vector<int> counts(size), displ(size, 0);
  MPI_Allgather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) displ[r] = displ[r - 1] + counts[r - 1];
  std::vector<long> all(displ[size - 1] + counts[size - 1]);
  MPI_Allgatherv(mine.data(), m, MPI_LONG, all.data(), counts.data(), displ.data(), MPI_LONG, comm);
  return all;
}

// Step 4: the components that touch a cut (records (id, grounded, count) of every rank) joined
// through the cut edges the same way on every rank: ids sorted, the smallest id the root.
struct CrossComponents {
  std::vector<long> sorted;         // the records' ids, ascending
  std::vector<long> parent;         // union-find over the indices of `sorted`
  std::vector<int> cross_id;        // per root index: its number among the floating ones, or -1
  std::vector<double> cross_count;  // per floating one: its cells over all ranks
  long index_of(long id) const {
    return long(std::lower_bound(sorted.begin(), sorted.end(), id) - sorted.begin());
  }
};

CrossComponents join_cross(const std::vector<long>& all_rec, const std::vector<long>& all_edges) {
  CrossComponents x;
  const long nrec = long(all_rec.size()) / 3;
  std::vector<long> ids(nrec);
  for (long r = 0; r < nrec; ++r) ids[r] = all_rec[3 * r];
  std::vector<long> order(nrec);
  std::iota(order.begin(), order.end(), 0L);
  std::sort(order.begin(), order.end(), [&](long p, long q) { return ids[p] < ids[q]; });
  x.sorted.resize(nrec);
  for (long r = 0; r < nrec; ++r) x.sorted[r] = ids[order[r]];
  x.parent.resize(nrec);
  std::iota(x.parent.begin(), x.parent.end(), 0L);
  for (size_t q = 0; q + 1 < all_edges.size(); q += 2)
    unite(x.parent, x.index_of(all_edges[q]), x.index_of(all_edges[q + 1]));
  std::vector<char> g_grounded(nrec, 0);
  std::vector<double> g_count(nrec, 0.0);
  for (long r = 0; r < nrec; ++r) {
    const long i = x.index_of(ids[r]), top = find_root(x.parent, i);
    if (all_rec[3 * r + 1]) g_grounded[top] = 1;
    g_count[top] += double(all_rec[3 * r + 2]);
  }
  x.cross_id.assign(nrec, -1);
  for (long i = 0; i < nrec; ++i)
    if (find_root(x.parent, i) == i && !g_grounded[i]) {
      x.cross_id[i] = int(x.cross_count.size());
      x.cross_count.push_back(g_count[i]);
    }
  return x;
}


}  // namespace

DistPoisson::DistPoisson(MPI_Comm comm, const GridBlocks& blocks, const pressure::GridSpec& global)
    : comm_(comm), blocks_(blocks), global_(global) {
  int size = 0, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  if (size != blocks.ranks() || rank != blocks.rank())
    throw Error(fmt::format("air pressure: blocks for rank {} of {} used on rank {} of {}", blocks.rank(),
                            blocks.ranks(), rank, size));
  if (std::array<int, 3>{global.nx, global.ny, global.nz} != blocks.global_cells())
    throw Error(fmt::format("air pressure: grid of {} x {} x {} cells given to blocks of {} x {} x {}", global.nx,
                            global.ny, global.nz, blocks.global_cells()[0], blocks.global_cells()[1],
                            blocks.global_cells()[2]));
  if (!(global.dx > 0) || !(global.dy > 0) || !(global.dz > 0)) throw Error("air pressure: grid spacings must be > 0");
  for (Boundary b : global.bc)
    if (b == Boundary::Periodic)
      throw Error("air pressure: periodic sides are not supported by the distributed solver "
                  "(use the serial make_pressure_solver)");
  const auto e = blocks.local_cells();
  nx_ = e[0], ny_ = e[1], nz_ = e[2];
  n_ = blocks.local_count();
}

pressure::GridSpec DistPoisson::local_spec(Boundary cut) const {
  pressure::GridSpec g = global_;
  g.nx = nx_, g.ny = ny_, g.nz = nz_;
  for (int s = 0; s < 6; ++s)
    if (blocks_.is_cut(s)) g.bc[s] = cut;
  return g;
}

// Checks on every rank (a bad array anywhere stops all of them), then the steps above.
void DistPoisson::set(const std::vector<double>& ax, const std::vector<double>& ay, const std::vector<double>& az) {
  const std::array<int, 3> e{nx_, ny_, nz_};
  const std::vector<double>* in[3] = {&ax, &ay, &az};
  const std::string why = coefficient_error(e, in);
  const bool ok = why.empty();
  // Bad input on one rank stops every rank (no one is left waiting in the exchange below).
  int all_ok = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all_ok, 1, MPI_INT, MPI_LAND, comm_);
  if (!ok) throw Error("air pressure: " + why);
  if (!all_ok) throw Error("air pressure: bad face coefficients on another rank");
  for (int a = 0; a < 3; ++a) a_[a] = *in[a];
  sync_cut_faces();
  assemble_weights();
  label_components();
}

// The cut face belongs to the upper block: it sends its face-0 layer down, and the lower
// block's copy (its face n) is overwritten with it.
void DistPoisson::sync_cut_faces() {
  const std::array<int, 3> e{nx_, ny_, nz_};
  for (int a = 0; a < 3; ++a) {
    const int lo = blocks_.neighbour(2 * a), hi = blocks_.neighbour(2 * a + 1);
    std::vector<double> out, back;
    MPI_Request rq[2];
    int nr = 0;
    if (hi >= 0) {
      back.resize(layer_count(e, a));
      MPI_Irecv(back.data(), int(back.size()), MPI_DOUBLE, hi, kTagCoef + a, comm_, &rq[nr++]);
    }
    if (lo >= 0) {
      out.resize(layer_count(e, a));
      for_layer(e, 2 * a, [&](long q, long c) { out[q] = a_[a][side_face(e, 2 * a, c)]; });
      MPI_Isend(out.data(), int(out.size()), MPI_DOUBLE, lo, kTagCoef + a, comm_, &rq[nr++]);
    }
    MPI_Waitall(nr, rq, MPI_STATUSES_IGNORE);
    if (hi >= 0) for_layer(e, 2 * a + 1, [&](long q, long c) { a_[a][side_face(e, 2 * a + 1, c)] = back[q]; });
  }
}

// Weights: interior and cut faces couple two cells; physical faces add the Open term. Every
// cell sums its faces in the order x, y, z, face index ascending.
void DistPoisson::assemble_weights() {
  const double h2[3] = {1 / (global_.dx * global_.dx), 1 / (global_.dy * global_.dy), 1 / (global_.dz * global_.dz)};
  diag_.assign(n_, 0.0);
  open_.assign(n_, 0.0);
  for (int a = 0; a < 3; ++a) {
    w_[a].assign(a_[a].size(), 0.0);
    std::array<long, 3> f{nx_, ny_, nz_};
    f[a] += 1;
    const long st = a == 0 ? 1 : (a == 1 ? nx_ : long(nx_) * ny_);  // cell stride along a
    for (long k = 0; k < f[2]; ++k)
      for (long j = 0; j < f[1]; ++j)
        for (long i = 0; i < f[0]; ++i) {
          const long q = i + f[0] * (j + f[1] * k);
          const long idx[3] = {i, j, k};
          const long m = idx[a];
          const double w = a_[a][q] * h2[a];
          // Cell above the face (index m along a) and below it (m - 1), in cell indices.
          std::array<long, 3> c{i, j, k};
          const long up = c[0] + long(nx_) * (c[1] + long(ny_) * c[2]);
          const long down = up - st;
          const bool has_lo = m > 0 || blocks_.is_cut(2 * a), has_hi = m < f[a] - 1 || blocks_.is_cut(2 * a + 1);
          if (has_lo && has_hi) {
            w_[a][q] = w;
            if (m > 0) diag_[down] += w;
            if (m < f[a] - 1) diag_[up] += w;
          } else if (m == 0 && global_.bc[2 * a] == Boundary::Open) {
            open_[up] += 2 * w;
          } else if (m == f[a] - 1 && global_.bc[2 * a + 1] == Boundary::Open) {
            open_[down] += 2 * w;
          }
        }
  }
  for (long c = 0; c < n_; ++c) diag_[c] += open_[c];
}

// Starts the exchange of the cell layers next to the cut sides (received into hr_).
void DistPoisson::exchange_layers(const double* x) {
  const std::array<int, 3> e{nx_, ny_, nz_};
  nreq_ = 0;
  for (int s = 0; s < 6; ++s) {
    const int nb = blocks_.neighbour(s);
    if (nb < 0) continue;
    hr_[s].resize(layer_count(e, s / 2));
    // The layer arriving through side s was sent by the neighbour through the opposite side.
    MPI_Irecv(hr_[s].data(), int(hr_[s].size()), MPI_DOUBLE, nb, kTagLayer + (s ^ 1), comm_, &req_[nreq_++]);
  }
  for (int s = 0; s < 6; ++s) {
    const int nb = blocks_.neighbour(s);
    if (nb < 0) continue;
    hs_[s].resize(layer_count(e, s / 2));
    double* buf = hs_[s].data();
    for_layer(e, s, [&](long q, long c) { buf[q] = x[c]; });
    MPI_Isend(hs_[s].data(), int(hs_[s].size()), MPI_DOUBLE, nb, kTagLayer + s, comm_, &req_[nreq_++]);
  }
}

void DistPoisson::exchange_finish() {
  MPI_Waitall(nreq_, req_, MPI_STATUSES_IGNORE);
  nreq_ = 0;
}

void DistPoisson::apply(const double* x, double* y) {
  exchange_layers(x);
  const int nx = nx_, ny = ny_, nz = nz_;
  const long plane = long(nx) * ny;
  zero_.assign(std::max(nx, 1), 0.0);
  const std::vector<double>& zero = zero_;
  const double* wx = w_[0].data();
  const double* wy = w_[1].data();
  const double* wz = w_[2].data();
  // Interior couplings (cut faces are added once the neighbours' layers arrive).
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const long c0 = long(nx) * (j + long(ny) * k);
      const double* xr = x + c0;
      double* yr = y + c0;
      const double* d = diag_.data() + c0;
      const double* wxr = wx + long(nx + 1) * (j + long(ny) * k);
      const bool s_in = j > 0, n_in = j < ny - 1, b_in = k > 0, t_in = k < nz - 1;
      const double* xs = s_in ? xr - nx : xr;
      const double* xn = n_in ? xr + nx : xr;
      const double* ws = s_in ? wy + long(nx) * (j + long(ny + 1) * k) : zero.data();
      const double* wn = n_in ? wy + long(nx) * (j + 1 + long(ny + 1) * k) : zero.data();
      const double* xb = b_in ? xr - plane : xr;
      const double* xt = t_in ? xr + plane : xr;
      const double* wb = b_in ? wz + c0 : zero.data();
      const double* wt = t_in ? wz + c0 + plane : zero.data();
      for (int i = 0; i < nx; ++i)
        yr[i] = d[i] * xr[i] - ws[i] * xs[i] - wn[i] * xn[i] - wb[i] * xb[i] - wt[i] * xt[i];
      for (int i = 1; i < nx; ++i) yr[i] -= wxr[i] * xr[i - 1];
      for (int i = 0; i < nx - 1; ++i) yr[i] -= wxr[i + 1] * xr[i + 1];
    }
  exchange_finish();
  const std::array<int, 3> e{nx, ny, nz};
  for (int s = 0; s < 6; ++s) {
    if (!blocks_.is_cut(s)) continue;
    const double* g = hr_[s].data();
    const double* w = w_[s / 2].data();
    for_layer(e, s, [&](long q, long c) { y[c] -= w[side_face(e, s, c)] * g[q]; });
  }
}

// Reads w_, open_ and the neighbours' labels; writes comp_, local_count_, cross_count_,
// isolated_, floating_cells_, n_floating_, singular_ and sizes local_sum_, cross_sum_. The
// labels do not depend on the order of the unions (union_find.hpp), so every rank joins the
// gathered components identically.
void DistPoisson::label_components() {
  const std::array<int, 3> e{nx_, ny_, nz_};
  const GlobalIds gid{e, blocks_.lo(), blocks_.global_cells()};
  // 1. Components of the block through its own faces.
  BlockComponents b = block_components(e, w_, open_);
  // 2. Labels of the cells next to each cut, exchanged; joined through faces with w > 0.
  const std::vector<long> edges = cut_edges(comm_, blocks_, e, w_, gid, b);
  // 3. The components that touch a cut, gathered on every rank: (gid, grounded, count).
  std::vector<long> rec;
  for (long c = 0; c < n_; ++c)
    if (b.root[c] == c && b.at_cut[c]) rec.insert(rec.end(), {gid(c), long(b.grounded[c]), long(b.count[c])});
  const std::vector<long> all_rec = gather_all(comm_, rec);
  const std::vector<long> all_edges = gather_all(comm_, edges);
  // 4. Join them the same way on every rank.
  CrossComponents x = join_cross(all_rec, all_edges);
  cross_count_ = x.cross_count;
  // 5. Per cell: grounded, local floating component, or floating component over ranks.
  comp_.assign(n_, -1);
  local_count_.clear();
  isolated_.clear();
  std::vector<int> local_id(n_, -1);
  int n_local = 0;
  for (long c = 0; c < n_; ++c) {
    const long r = b.root[c];
    if (b.at_cut[r]) {
      const int q = x.cross_id[find_root(x.parent, x.index_of(gid(r)))];
      if (q >= 0) comp_[c] = -2 - q;
      continue;
    }
    if (b.grounded[r]) continue;
    if (b.count[r] == 1) {
      isolated_.push_back(c);
      continue;
    }
    if (local_id[r] < 0) {
      local_id[r] = n_local++;
      local_count_.push_back(b.count[r]);
    }
    comp_[c] = local_id[r];
  }
  floating_cells_.clear();
  for (long c = 0; c < n_; ++c)
    if (comp_[c] != -1) floating_cells_.push_back(c);
  int n_float = n_local + int(isolated_.size());
  MPI_Allreduce(MPI_IN_PLACE, &n_float, 1, MPI_INT, MPI_SUM, comm_);
  n_floating_ = n_float + int(cross_count_.size());
  singular_ = n_floating_ > 0;
  local_sum_.assign(local_count_.size(), 0.0);
  cross_sum_.assign(cross_count_.size(), 0.0);
}

void DistPoisson::project_floating(double* v) {
  for (long c : isolated_) v[c] = 0.0;
  if (local_count_.empty() && cross_count_.empty()) return;
  std::fill(local_sum_.begin(), local_sum_.end(), 0.0);
  std::fill(cross_sum_.begin(), cross_sum_.end(), 0.0);
  for (long c : floating_cells_) {  // ascending cell order
    const int q = comp_[c];
    if (q >= 0) local_sum_[q] += v[c];
    else cross_sum_[-2 - q] += v[c];
  }
  // The list of components over ranks is the same on every rank, so all take this branch.
  if (!cross_sum_.empty())
    MPI_Allreduce(MPI_IN_PLACE, cross_sum_.data(), int(cross_sum_.size()), MPI_DOUBLE, MPI_SUM, comm_);
  for (size_t q = 0; q < local_sum_.size(); ++q) local_sum_[q] /= local_count_[q];
  for (size_t q = 0; q < cross_sum_.size(); ++q) cross_sum_[q] /= cross_count_[q];
  for (long c : floating_cells_) {
    const int q = comp_[c];
    v[c] -= q >= 0 ? local_sum_[q] : cross_sum_[-2 - q];
  }
}

}  // namespace cgdem::air_mpi
