// The 7-point variable-coefficient operator of pressure_solver.hpp, in SPD form:
//
//     (A phi)_c = sum_f w_f (phi_c - phi_nb(f)) + sum_{open f} 2 w_f phi_c ,   w_f = a_f / h_f^2,
//
// i.e. A = -div(a grad .), so div(a grad phi) = rhs  <=>  A phi = -rhs.  On an Open face the
// ghost value is -phi_c (phi = 0 on the face), which gives the 2 w_f phi_c term; Wall faces carry
// nothing; the Periodic wrap face of an axis is face 0 of that axis.
//
// Connectivity: cells joined by faces with w_f > 0 form components. A component with no Open face
// of positive coefficient is "floating": A is singular on it (constant null vector). Solvers make
// the right-hand side mean-free on each floating component and return phi mean-free on it
// (project_floating); a cell whose faces are all blocked is a floating component of one cell and
// gets phi = 0.
//
// Reads: GridSpec and the face coefficients given to set(). Writes: only its own arrays.
#pragma once
#include <vector>

#include "solvers/pressure/active_rows.hpp"
#include "solvers/pressure/pressure_solver.hpp"

namespace cgdem::pressure {

class Poisson7 {
 public:
  explicit Poisson7(const GridSpec& g);  // validates the grid (throws cgdem::Error)

  // Face coefficients a >= 0 in the MAC layout of pressure_solver.hpp (throws on size/sign).
  void set(const std::vector<double>& ax, const std::vector<double>& ay, const std::vector<double>& az);

  // y = A x (both of length cells()); OpenMP over (j,k) rows, result independent of threads.
  // Only the active rows' segments (active()) are computed; y = 0 on the other cells (what
  // A x is there for finite x, up to the sign of zero).
  void apply(const double* x, double* y) const;
  // r = b - A x (r = b outside the active segments)
  void residual(const double* b, const double* x, double* r) const;
  // y = A x and returns x . y (row partial sums added in row order: independent of threads).
  double apply_dot(const double* x, double* y) const;
  // One Gauss-Seidel half-sweep over the cells with (i+j+k) % 2 == color:
  //   x_c = (b_c + sum_nb w_f x_nb) / D_c   (cells with D_c = 0 are left alone);
  // omega != 1: over-relaxed, x_c += omega ((b_c + sum_nb w_f x_nb) / D_c - x_c).
  void gauss_seidel_color(const double* b, double* x, int color, double omega = 1.0) const;
  // The two half-sweeps `first` then 1 - first in one pass over memory: the second colour of
  // plane k-1 is updated right after the first colour of plane k (its last neighbour to
  // change). Bitwise the same as gauss_seidel_color(first) then (1 - first), for any number of
  // threads (each thread's chunk of planes defers the second colour of its two end planes until
  // all threads have done their first colour).
  void gauss_seidel_pair(const double* b, double* x, int first, double omega = 1.0) const;
  // Subtract, on every floating component, its mean (deterministic serial sums).
  // zero_outside: v is already 0 on the cells outside active(); only the one-cell components
  // inside its segments are set to 0 (the same result with far fewer writes).
  void project_floating(double* v, bool zero_outside = false) const;

  const GridSpec& grid() const { return g_; }
  long n() const { return g_.cells(); }
  const std::vector<double>& diag() const { return diag_; }
  // The face coefficients a as given to set().
  const std::vector<double>& ax() const { return ax_; }
  const std::vector<double>& ay() const { return ay_; }
  const std::vector<double>& az() const { return az_; }
  // Weights w = a/h^2 on faces (MAC layout; non-periodic boundary faces hold 0, the periodic
  // wrap face is face 0). Open-face weights are in open_x/y/z (0 unless the side is Open).
  const std::vector<double>& wx() const { return wx_; }
  const std::vector<double>& wy() const { return wy_; }
  const std::vector<double>& wz() const { return wz_; }
  // 2 w_f of the Open boundary faces, summed per cell (already included in diag()).
  const std::vector<double>& open_diag() const { return open_; }
  bool singular() const { return n_floating_ > 0; }
  int floating_components() const { return n_floating_; }
  // Component id of a floating cell, -1 for a grounded cell.
  const std::vector<int>& floating_id() const { return comp_; }
  // The cells with D > 0 as row segments (active_rows.hpp), updated by set() whenever the
  // pattern of positive weights changes.
  const ActiveRows& active() const { return active_; }
  bool periodic(int axis) const { return g_.bc[2 * axis] == Boundary::Periodic; }

 private:
  // The steps of set(): the weights of the x and y faces, then of the z faces (writes
  // wx_, wy_, wz_; adds to diag_ and open_, zeroed before; see set() for the order of sums).
  void add_xy_faces(const std::vector<double>& ax, const std::vector<double>& ay);
  void add_z_faces(const std::vector<double>& az);
  void label_components();
  template <bool kResidual>
  void apply_rows(const double* x, double* y, const double* b, double* row_dot = nullptr) const;
  mutable std::vector<double> row_dot_;
  void gs_row(const double* b, double* x, int j, int k, int color, double omega) const;

  GridSpec g_;
  std::vector<double> ax_, ay_, az_, wx_, wy_, wz_, diag_, open_;
  std::vector<double> old_w_[4];  // set(): the previous wx_, wy_, wz_, open_ (compared, then reused)
  std::vector<int> comp_;
  std::vector<long> floating_cells_;  // cells of floating components, ascending
  std::vector<long> isolated_cells_, shared_cells_;  // of one-cell / larger floating components
  std::vector<long> isolated_active_;                 // the isolated cells inside active()'s segments
  std::vector<double> comp_count_;
  // The larger floating components numbered apart (0 .. shared_count_.size() - 1): the number
  // of each cell of shared_cells_, and their cell counts. The one-cell components are most of
  // them on a grid with walls (every blocked cell is one), and project_floating only sums over
  // the others.
  std::vector<int> shared_comp_;
  std::vector<double> shared_count_;
  int n_floating_ = 0;
  ActiveRows active_;
};

// Loops shorter than this run serially: tiny OpenMP regions only cost barriers (badly so on a
// loaded machine), and the arithmetic is the same either way.
inline constexpr long kParallelMin = 32768;

// Deterministic helpers on plain arrays (fixed blocking: sums do not depend on thread count).
double dot(const double* a, const double* b, long n);
inline double norm2(const double* a, long n);

}  // namespace cgdem::pressure

#include <cmath>
inline double cgdem::pressure::norm2(const double* a, long n) { return std::sqrt(dot(a, a, n)); }
