// Proper orthogonal decomposition by the method of snapshots (Sirovich 1987, Q. Appl.
// Math. 45, 561-571), and principal angles between subspaces (Bjorck & Golub 1973, Math.
// Comp. 27, 579-594).
//
// Snapshots x_j (j = 1..m) of a field on n cells are the columns of X (n x m); with
// subtract_mean the temporal mean is removed from every row first (POD of the fluctuation).
// Method of snapshots: the m x m correlation matrix
//   C = X^T X,  C v_k = lambda_k v_k,  lambda_1 >= lambda_2 >= ... >= 0          (P1)
// gives the modal energies lambda_k (sum_k lambda_k = ||X||_F^2) and the orthonormal
// spatial modes
//   phi_k = X v_k / sqrt(lambda_k)                                              (P2)
// which are the left singular vectors of the thin SVD X = Phi Sigma V^T, sigma_k^2 =
// lambda_k. m << n here (tens of snapshots, up to 10^5 cells), so C is small; modes with
// lambda_k <= 1e-12 lambda_1 carry no energy and are dropped.
//
// Principal angles between span(A) and span(B) (A: n x p, B: n x q, p <= q after
// orthonormalising both by Householder QR):
//   cos theta_i = sigma_i(Q_A^T Q_B),  0 <= theta_1 <= ... <= theta_p <= pi/2     (P3)
// theta = 0: a shared direction; pi/2: orthogonal.
#pragma once
#include <Eigen/Dense>

namespace cgdem::scaling {

struct Pod {
  Eigen::VectorXd energy;  // lambda_k, descending
  Eigen::MatrixXd modes;   // phi_k as columns (n x r), orthonormal
  Eigen::VectorXd mean;    // the removed temporal mean (zeros without subtract_mean)
  double total = 0;        // sum of lambda_k = ||X - mean||_F^2
};

// X: n x m, m >= 1. Throws cgdem::Error on an empty X or non-finite entries.
Pod pod_snapshots(const Eigen::MatrixXd& X, bool subtract_mean);

// Smallest r with sum_{k<=r} lambda_k >= fraction * total (at least 1, at most all modes).
int modes_for_energy(const Pod& p, double fraction);

// Angles (P3) in radians, ascending; min(p, q) of them. Throws on different row counts or
// an empty basis.
Eigen::VectorXd principal_angles(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

}  // namespace cgdem::scaling
