// POD by the method of snapshots and principal angles (scaling/pod.hpp) against closed forms.
//  * A field built from three known orthonormal spatial modes phi_k with orthonormal,
//    zero-mean temporal coefficients and amplitudes sigma_k (plus a constant mean field that
//    subtract_mean must remove) has modal energies exactly sigma_k^2 and its leading modes
//    span exactly span(phi_1..3): principal angles 0. Tolerances: 1e-10 relative on the
//    energies, 1e-6 rad on the angles (acos near 1 resolves ~1e-8).
//  * Principal angles of subspaces with prescribed angles (0.3 and 1.1 rad) are recovered
//    from non-orthonormal bases to 1e-12 rad.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "scaling/pod.hpp"

namespace cgdem::scaling {
namespace {

TEST(ScalingPod, RecoversKnownModesAndEnergies) {
  const int n = 240, m = 36;
  const double pi = std::numbers::pi;
  Eigen::MatrixXd phi(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) phi(i, k) = std::sin(pi * (k + 1) * (i + 0.5) / n);  // orthogonal on the midpoints
  for (int k = 0; k < 3; ++k) phi.col(k).normalize();
  const double sigma[3] = {5.0, 2.0, 0.5};
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, m);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < m; ++j) X.col(j) += sigma[k] * phi.col(k) * std::sqrt(2.0 / m) * std::cos(2 * pi * (k + 1) * j / m);
  Eigen::VectorXd mean(n);
  for (int i = 0; i < n; ++i) mean(i) = 3.0 + std::cos(0.1 * i);
  X.colwise() += mean;
  const Pod p = pod_snapshots(X, true);
  ASSERT_EQ(p.energy.size(), 3) << "modes with energy above 1e-12 of the first";
  double worst = 0;
  for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(p.energy(k) - sigma[k] * sigma[k]) / (sigma[k] * sigma[k]));
  std::printf("POD energies %.12g %.12g %.12g (want 25, 4, 0.25): worst relative error %.2e (tol 1e-10)\n",
              p.energy(0), p.energy(1), p.energy(2), worst);
  EXPECT_LT(worst, 1e-10);
  EXPECT_NEAR(p.total, 25 + 4 + 0.25, 1e-9);
  EXPECT_LT((p.mean - mean).norm() / mean.norm(), 1e-12);
  const Eigen::MatrixXd G = p.modes.transpose() * p.modes;
  EXPECT_LT((G - Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-10) << "modes orthonormal";
  const Eigen::VectorXd th = principal_angles(phi, p.modes);
  std::printf("principal angles to the true modes: %.2e %.2e %.2e rad (tol 1e-6)\n", th(0), th(1), th(2));
  EXPECT_LT(th.maxCoeff(), 1e-6);
  EXPECT_EQ(modes_for_energy(p, 0.85), 1);  // 25 / 29.25 = 0.855
  EXPECT_EQ(modes_for_energy(p, 0.99), 2);  // 29 / 29.25 = 0.991
  EXPECT_EQ(modes_for_energy(p, 0.999), 3);
  // The thin SVD of the centred snapshots gives the same energies (sigma^2).
  Eigen::BDCSVD<Eigen::MatrixXd> svd(X.colwise() - mean);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(svd.singularValues()(k) * svd.singularValues()(k), p.energy(k), 1e-9);
}

TEST(ScalingPod, PrincipalAnglesOfKnownSubspaces) {
  const int n = 6;
  const double a = 0.3, b = 1.1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, 2), B = Eigen::MatrixXd::Zero(n, 2);
  A(0, 0) = 1, A(1, 1) = 1;
  B(0, 0) = std::cos(a), B(2, 0) = std::sin(a);
  B(1, 1) = std::cos(b), B(3, 1) = std::sin(b);
  // Non-orthonormal bases of the same subspaces: mix and scale the columns.
  Eigen::Matrix2d mix;
  mix << 2.0, 0.5, -1.0, 3.0;
  const Eigen::VectorXd th = principal_angles(A * mix, B * mix.transpose());
  std::printf("principal angles %.15f %.15f (want %.15f %.15f): errors %.2e %.2e (tol 1e-12)\n", th(0), th(1), a, b,
              std::fabs(th(0) - a), std::fabs(th(1) - b));
  EXPECT_NEAR(th(0), a, 1e-12);
  EXPECT_NEAR(th(1), b, 1e-12);
  // A subspace against itself and against its orthogonal complement.
  EXPECT_LT(principal_angles(A, A * mix).maxCoeff(), 1e-7);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, 2);
  C(4, 0) = 1, C(5, 1) = 1;
  EXPECT_NEAR(principal_angles(A, C).minCoeff(), std::numbers::pi / 2, 1e-12);
}

TEST(ScalingPod, RejectsBadInput) {
  EXPECT_THROW(pod_snapshots(Eigen::MatrixXd(0, 3), true), std::exception);
  Eigen::MatrixXd X = Eigen::MatrixXd::Ones(4, 3);
  X(1, 1) = NAN;
  EXPECT_THROW(pod_snapshots(X, false), std::exception);
  EXPECT_THROW(principal_angles(Eigen::MatrixXd::Ones(4, 1), Eigen::MatrixXd::Ones(5, 1)), std::exception);
}

}  // namespace
}  // namespace cgdem::scaling
