// The cells of a pressure grid that take part in the solve, as segments of x rows.
//
// A cell whose faces are all blocked (D_c = 0: inside a wall, including a moving one) is a
// one-cell floating component of the operator (poisson7.hpp). Whatever is stored there, it
// enters the rows of its neighbours only through faces of weight 0, and the solvers set phi = 0
// there at the end. On the die-filling grid more than half of the cells are such cells (the
// table under its top, the walls of the shoe), so the loops that run once per PCG iteration on
// the finest grid (A x, and the smoother, restriction, prolongation and transfers of the
// multigrid's finest level) visit only the segments listed here and skip the rest.
//
// Row r = j + ny k holds the segments begin(r) .. end(r) - 1, each the cells [lo(s), hi(s)) of
// the row in ascending order. A run of fewer than kMergeGap skipped cells between two active
// ones is kept inside one segment (it is computed like the active cells: cheaper than a second
// segment). A row without an active cell has no segment.
//
// Work sharing: share() hands each thread a contiguous range of rows, balanced by the cells in
// segments plus a fixed cost per row; share_planes() the same by planes (the multigrid's fused
// red-black pair needs whole planes). Every loop that uses them computes each row alone (or,
// for the red-black pair, in an order whose result does not depend on the split), so the
// results do not depend on the number of threads.
#pragma once
#include <vector>

namespace cgdem::pressure {

class ActiveRows {
 public:
  static constexpr int kMergeGap = 8;
  static constexpr long kRowCost = 16;  // the fixed cost of a row in share(), in cells

  // Every cell of an nx x ny x nz grid (one segment per row).
  void all(int nx, int ny, int nz);
  // The cells with diag > 0 (diag: nx ny nz values, x fastest). whole_rows: a row with an
  // active cell is the single segment [0, nx) (a periodic x axis joins its two ends).
  void from_diag(const double* diag, int nx, int ny, int nz, bool whole_rows);
  // The cells with mask != 0, likewise.
  void from_mask(const unsigned char* mask, int nx, int ny, int nz, bool whole_rows);
  // Marks in mask (of the grid coarsened by 2 per axis, ceil(n/2) cells) every coarse cell with
  // a fine cell inside a segment.
  void mark_parents(unsigned char* mask) const;
  // The same segments on the same grid.
  bool operator==(const ActiveRows& o) const {
    return nx_ == o.nx_ && ny_ == o.ny_ && nz_ == o.nz_ && off_ == o.off_ && lo_ == o.lo_ && hi_ == o.hi_;
  }

  int rows() const { return static_cast<int>(off_.size()) - 1; }
  int begin(int r) const { return off_[r]; }
  int end(int r) const { return off_[r + 1]; }
  int lo(int s) const { return lo_[s]; }
  int hi(int s) const { return hi_[s]; }
  // Cells inside segments, over the whole grid.
  long cells() const { return cells_; }

  // Rows [r0, r1) of thread t of nth (the ranges cover all rows, in order).
  void share(int t, int nth, int& r0, int& r1) const { split(row_work_, t, nth, r0, r1); }
  // Planes [k0, k1) of thread t of nth.
  void share_planes(int t, int nth, int& k0, int& k1) const { split(plane_work_, t, nth, k0, k1); }
  // Rows [R0, R1) of the grid coarsened by 2 per axis (ceil(n/2) cells), balanced by the fine
  // rows each coarse row covers: for the restriction.
  void share_coarse(int t, int nth, int& r0, int& r1) const { split(coarse_work_, t, nth, r0, r1); }

 private:
  template <class Active>
  void build(Active active, int nx, int ny, int nz, bool whole_rows);
  void finish(int nx, int ny, int nz);
  static void split(const std::vector<long>& prefix, int t, int nth, int& a, int& b);

  std::vector<int> off_{0}, lo_, hi_;
  std::vector<long> row_work_{0}, plane_work_{0}, coarse_work_{0};  // prefix sums
  long cells_ = 0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
};

}  // namespace cgdem::pressure
