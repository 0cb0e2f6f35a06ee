#include "scaling/pod.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace cgdem::scaling {

Pod pod_snapshots(const Eigen::MatrixXd& X0, bool subtract_mean) {
  if (X0.rows() == 0 || X0.cols() == 0) throw Error("POD: no snapshots or an empty field");
  if (!X0.allFinite()) throw Error("POD: the snapshots hold non-finite values");
  Pod p;
  p.mean = subtract_mean ? Eigen::VectorXd(X0.rowwise().mean()) : Eigen::VectorXd::Zero(X0.rows());
  const Eigen::MatrixXd X = X0.colwise() - p.mean;
  const Eigen::MatrixXd C = X.transpose() * X;  // (P1)
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(C);
  if (es.info() != Eigen::Success) throw Error("POD: the eigen-solver of the correlation matrix failed");
  // Eigen returns ascending eigenvalues: reverse, drop the ones without energy.
  const Eigen::Index m = C.rows();
  const double top = std::max(0.0, es.eigenvalues()(m - 1));
  int r = 0;
  for (Eigen::Index k = m - 1; k >= 0; --k)
    if (es.eigenvalues()(k) > 1e-12 * top && top > 0) ++r;
  p.energy.resize(r);
  p.modes.resize(X.rows(), r);
  for (int k = 0; k < r; ++k) {
    const double lambda = es.eigenvalues()(m - 1 - k);
    p.energy(k) = lambda;
    p.modes.col(k) = X * es.eigenvectors().col(m - 1 - k) / std::sqrt(lambda);  // (P2)
  }
  p.total = X.squaredNorm();
  return p;
}

int modes_for_energy(const Pod& p, double fraction) {
  double sum = 0;
  for (int k = 0; k < p.energy.size(); ++k) {
    sum += p.energy(k);
    if (sum >= fraction * p.total) return k + 1;
  }
  return std::max<int>(1, static_cast<int>(p.energy.size()));
}

Eigen::VectorXd principal_angles(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  if (A.rows() != B.rows()) throw Error("principal angles: the bases live in spaces of different dimension");
  if (A.cols() == 0 || B.cols() == 0) throw Error("principal angles: an empty basis");
  auto orthonormal = [](const Eigen::MatrixXd& M) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(M);
    return Eigen::MatrixXd(qr.householderQ() * Eigen::MatrixXd::Identity(M.rows(), M.cols()));
  };
  const Eigen::MatrixXd QA = orthonormal(A), QB = orthonormal(B);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(QA.transpose() * QB);  // (P3)
  Eigen::VectorXd s = svd.singularValues();                     // descending
  Eigen::VectorXd theta(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) theta(i) = std::acos(std::clamp(s(i), -1.0, 1.0));
  return theta;  // ascending, as the cosines descend
}

}  // namespace cgdem::scaling
