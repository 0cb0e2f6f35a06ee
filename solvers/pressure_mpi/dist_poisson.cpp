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

void DistPoisson::set(const std::vector<double>& ax, const std::vector<double>& ay, const std::vector<double>& az) {
  const std::array<int, 3> e{nx_, ny_, nz_};
  const std::vector<double>* in[3] = {&ax, &ay, &az};
  bool ok = true;
  std::string why;
  for (int a = 0; a < 3; ++a) {
    if (long(in[a]->size()) != face_count(e, a)) {
      ok = false;
      why = fmt::format("face coefficient array a{} has {} entries, expected {}", "xyz"[a], in[a]->size(),
                        face_count(e, a));
      break;
    }
    for (double v : *in[a])
      if (!(v >= 0.0) || !std::isfinite(v)) {
        ok = false;
        why = fmt::format("face coefficient a{} must be finite and >= 0", "xyz"[a]);
      }
  }
  // Bad input on one rank stops every rank (no one is left waiting in the exchange below).
  int all_ok = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all_ok, 1, MPI_INT, MPI_LAND, comm_);
  if (!ok) throw Error("air pressure: " + why);
  if (!all_ok) throw Error("air pressure: bad face coefficients on another rank");
  for (int a = 0; a < 3; ++a) a_[a] = *in[a];

  // The cut face belongs to the upper block: it sends its face-0 layer down.
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

  // Weights: interior and cut faces couple two cells; physical faces add the Open term.
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
  label_components();
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

void DistPoisson::label_components() {
  const std::array<int, 3> e{nx_, ny_, nz_};
  const auto& gn = blocks_.global_cells();
  const auto& lo = blocks_.lo();
  // 1. Components of the block through its own faces.
  std::vector<long> parent(n_);
  std::iota(parent.begin(), parent.end(), 0L);
  for (int k = 0; k < nz_; ++k)
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const long c = i + long(nx_) * (j + long(ny_) * k);
        if (i > 0 && w_[0][i + long(nx_ + 1) * (j + long(ny_) * k)] > 0) unite(parent, c, c - 1);
        if (j > 0 && w_[1][i + long(nx_) * (j + long(ny_ + 1) * k)] > 0) unite(parent, c, c - nx_);
        if (k > 0 && w_[2][c] > 0) unite(parent, c, c - long(nx_) * ny_);
      }
  std::vector<long> root(n_);
  for (long c = 0; c < n_; ++c) root[c] = find_root(parent, c);
  std::vector<char> grounded(n_, 0), at_cut(n_, 0);
  std::vector<double> count(n_, 0.0);
  for (long c = 0; c < n_; ++c) {
    if (open_[c] > 0) grounded[root[c]] = 1;
    count[root[c]] += 1;
  }
  // Global id of a local root: the global index of its cell (unique over the ranks, exact in
  // a double for any grid this code can hold).
  auto gid = [&](long c) {
    const long i = c % nx_, j = (c / nx_) % ny_, k = c / (long(nx_) * ny_);
    return (lo[0] + i) + long(gn[0]) * ((lo[1] + j) + long(gn[1]) * (lo[2] + k));
  };
  // 2. Labels of the cells next to each cut, exchanged; joined through faces with w > 0.
  std::vector<long> edges;  // pairs (own root gid, neighbour root gid), from the upper sides
  {
    std::vector<double> out[6], in[6];
    MPI_Request rq[12];
    int nr = 0;
    for (int s = 0; s < 6; ++s) {
      const int nb = blocks_.neighbour(s);
      if (nb < 0) continue;
      in[s].resize(layer_count(e, s / 2));
      MPI_Irecv(in[s].data(), int(in[s].size()), MPI_DOUBLE, nb, kTagLabel + (s ^ 1), comm_, &rq[nr++]);
      out[s].resize(in[s].size());
      for_layer(e, s, [&](long q, long c) { out[s][q] = double(gid(root[c])); });
      MPI_Isend(out[s].data(), int(out[s].size()), MPI_DOUBLE, nb, kTagLabel + s, comm_, &rq[nr++]);
    }
    MPI_Waitall(nr, rq, MPI_STATUSES_IGNORE);
    for (int s = 0; s < 6; ++s) {
      if (!blocks_.is_cut(s)) continue;
      const double* w = w_[s / 2].data();
      for_layer(e, s, [&](long q, long c) {
        if (!(w[side_face(e, s, c)] > 0)) return;
        at_cut[root[c]] = 1;
        if (s % 2) edges.insert(edges.end(), {gid(root[c]), long(in[s][q])});
      });
    }
  }
  // 3. The components that touch a cut, gathered on every rank: (gid, grounded, count).
  std::vector<long> rec;
  for (long c = 0; c < n_; ++c)
    if (root[c] == c && at_cut[c]) rec.insert(rec.end(), {gid(c), long(grounded[c]), long(count[c])});
  int size = 0;
  MPI_Comm_size(comm_, &size);
  auto gather = [&](const std::vector<long>& mine) {
    int m = int(mine.size());
    std::vector<int> counts(size), displ(size, 0);
    MPI_Allgather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
    for (int r = 1; r < size; ++r) displ[r] = displ[r - 1] + counts[r - 1];
    std::vector<long> all(displ[size - 1] + counts[size - 1]);
    MPI_Allgatherv(mine.data(), m, MPI_LONG, all.data(), counts.data(), displ.data(), MPI_LONG, comm_);
    return all;
  };
  const std::vector<long> all_rec = gather(rec), all_edges = gather(edges);
  // 4. Join them the same way on every rank: ids sorted, the smallest id is the root.
  const long nrec = long(all_rec.size()) / 3;
  std::vector<long> ids(nrec);
  for (long r = 0; r < nrec; ++r) ids[r] = all_rec[3 * r];
  std::vector<long> order(nrec);
  std::iota(order.begin(), order.end(), 0L);
  std::sort(order.begin(), order.end(), [&](long p, long q) { return ids[p] < ids[q]; });
  std::vector<long> sorted(nrec);
  for (long r = 0; r < nrec; ++r) sorted[r] = ids[order[r]];
  auto index_of = [&](long id) { return long(std::lower_bound(sorted.begin(), sorted.end(), id) - sorted.begin()); };
  std::vector<long> gparent(nrec);
  std::iota(gparent.begin(), gparent.end(), 0L);
  for (size_t q = 0; q + 1 < all_edges.size(); q += 2) unite(gparent, index_of(all_edges[q]), index_of(all_edges[q + 1]));
  std::vector<char> g_grounded(nrec, 0);
  std::vector<double> g_count(nrec, 0.0);
  for (long r = 0; r < nrec; ++r) {
    const long x = index_of(ids[r]), top = find_root(gparent, x);
    if (all_rec[3 * r + 1]) g_grounded[top] = 1;
    g_count[top] += double(all_rec[3 * r + 2]);
  }
  std::vector<int> cross_id(nrec, -1);
  cross_count_.clear();
  for (long x = 0; x < nrec; ++x)
    if (find_root(gparent, x) == x && !g_grounded[x]) {
      cross_id[x] = int(cross_count_.size());
      cross_count_.push_back(g_count[x]);
    }
  // 5. Per cell: grounded, local floating component, or floating component over ranks.
  comp_.assign(n_, -1);
  local_count_.clear();
  isolated_.clear();
  std::vector<int> local_id(n_, -1);
  int n_local = 0;
  for (long c = 0; c < n_; ++c) {
    const long r = root[c];
    if (at_cut[r]) {
      const int q = cross_id[find_root(gparent, index_of(gid(r)))];
      if (q >= 0) comp_[c] = -2 - q;
      continue;
    }
    if (grounded[r]) continue;
    if (count[r] == 1) {
      isolated_.push_back(c);
      continue;
    }
    if (local_id[r] < 0) {
      local_id[r] = n_local++;
      local_count_.push_back(count[r]);
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
