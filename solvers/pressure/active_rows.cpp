// Segments of the active cells of a pressure grid; see active_rows.hpp.
#include "solvers/pressure/active_rows.hpp"

#include <algorithm>

namespace cgdem::pressure {

void ActiveRows::all(int nx, int ny, int nz) {
  const int rows = ny * nz;
  off_.resize(rows + 1);
  lo_.assign(rows, 0);
  hi_.assign(rows, nx);
  for (int r = 0; r <= rows; ++r) off_[r] = r;
  finish(nx, ny, nz);
}

void ActiveRows::from_diag(const double* diag, int nx, int ny, int nz, bool whole_rows) {
  build([diag](long c) { return diag[c] > 0; }, nx, ny, nz, whole_rows);
}

void ActiveRows::from_mask(const unsigned char* mask, int nx, int ny, int nz, bool whole_rows) {
  build([mask](long c) { return mask[c] != 0; }, nx, ny, nz, whole_rows);
}

void ActiveRows::mark_parents(unsigned char* mask) const {
  const long cnx = (nx_ + 1) / 2, cny = (ny_ + 1) / 2;
  for (int r = 0; r < rows(); ++r) {
    const int j = r % ny_, k = r / ny_;
    unsigned char* m = mask + cnx * (j / 2 + cny * (k / 2));
    for (int q = begin(r); q < end(r); ++q)
      for (int i = lo(q); i < hi(q); ++i) m[i / 2] = 1;
  }
}

template <class Active>
void ActiveRows::build(Active active, int nx, int ny, int nz, bool whole_rows) {
  const int rows = ny * nz;
  off_.assign(1, 0);
  lo_.clear();
  hi_.clear();
  for (int r = 0; r < rows; ++r) {
    const long c0 = static_cast<long>(nx) * r;
    int i = 0;
    while (i < nx) {
      while (i < nx && !active(c0 + i)) ++i;
      if (i == nx) break;
      const int a = i;
      while (i < nx && active(c0 + i)) ++i;
      if (whole_rows) {
        lo_.push_back(0), hi_.push_back(nx);
        break;
      }
      // A short gap after the last segment of this row: extend that segment instead.
      if (static_cast<int>(lo_.size()) > off_.back() && a - hi_.back() < kMergeGap) hi_.back() = i;
      else lo_.push_back(a), hi_.push_back(i);
    }
    off_.push_back(static_cast<int>(lo_.size()));
  }
  finish(nx, ny, nz);
}

void ActiveRows::finish(int nx, int ny, int nz) {
  nx_ = nx, ny_ = ny, nz_ = nz;
  const int rows = ny * nz;
  row_work_.assign(rows + 1, 0);
  cells_ = 0;
  for (int r = 0; r < rows; ++r) {
    long c = 0;
    for (int s = off_[r]; s < off_[r + 1]; ++s) c += hi_[s] - lo_[s];
    cells_ += c;
    row_work_[r + 1] = row_work_[r] + c + kRowCost;
  }
  plane_work_.assign(nz + 1, 0);
  for (int k = 0; k < nz; ++k) plane_work_[k + 1] = row_work_[long(ny) * (k + 1)];
  // Coarse rows (J, K) cover the fine rows j in {2J, 2J + 1}, k in {2K, 2K + 1} (fewer at an
  // odd edge).
  const int cny = (ny + 1) / 2, cnz = (nz + 1) / 2;
  coarse_work_.assign(long(cny) * cnz + 1, 0);
  for (int K = 0; K < cnz; ++K)
    for (int J = 0; J < cny; ++J) {
      long w = 0;
      for (int k = 2 * K; k <= std::min(2 * K + 1, nz - 1); ++k)
        for (int j = 2 * J; j <= std::min(2 * J + 1, ny - 1); ++j) {
          const long r = j + long(ny) * k;
          w += row_work_[r + 1] - row_work_[r];
        }
      const long R = J + long(cny) * K;
      coarse_work_[R + 1] = coarse_work_[R] + w;
    }
}

// Items [a, b) for thread t: the first item whose prefix reaches t/nth of the total, up to
// that of thread t + 1; the last thread ends at the last item.
void ActiveRows::split(const std::vector<long>& prefix, int t, int nth, int& a, int& b) {
  const int items = static_cast<int>(prefix.size()) - 1;
  const long total = prefix.back();
  auto first_reaching = [&](int q) {
    if (q <= 0) return 0;
    if (q >= nth) return items;
    const long target = total * q / nth;
    return static_cast<int>(std::lower_bound(prefix.begin(), prefix.end() - 1, target) - prefix.begin());
  };
  a = first_reaching(t);
  b = first_reaching(t + 1);
}

}  // namespace cgdem::pressure
