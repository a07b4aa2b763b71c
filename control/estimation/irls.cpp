// IRLS with Huber weights (see the header).
#include "estimation/irls.hpp"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>

namespace mrqp::estimation {

IrlsResult irlsEstimate(const Eigen::MatrixXd& Y, const Eigen::VectorXd& mu, const Eigen::VectorXd& sigma,
                        const IrlsOptions& options) {
  if (Y.rows() != mu.size() || Y.rows() != sigma.size() || Y.rows() == 0 || Y.cols() == 0)
    throw std::invalid_argument("irlsEstimate: Y, mu and sigma must have the same, non-zero number of rows");
  if (!Y.allFinite() || !mu.allFinite() || !sigma.allFinite() || sigma.minCoeff() <= 0.0)
    throw std::invalid_argument("irlsEstimate: non-finite data or non-positive sigma");
  const Eigen::Index n = Y.rows();
  const Eigen::MatrixXd Ys = sigma.cwiseInverse().asDiagonal() * Y;
  const Eigen::VectorXd ms = mu.cwiseQuotient(sigma);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  IrlsResult result;
  result.theta = Eigen::VectorXd::Zero(Y.cols());
  if (options.max_iterations < 1 || !(options.huber_k > 0.0))
    throw std::invalid_argument("irlsEstimate: max_iterations must be >= 1 and huber_k > 0");
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ys);  // iteration 1 refactors it with unit weights
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::VectorXd sw = w.cwiseSqrt();
    qr.compute(sw.asDiagonal() * Ys);
    const Eigen::VectorXd theta = qr.solve(sw.asDiagonal() * ms);
    const double change = (theta - result.theta).norm() / std::max(theta.norm(), 1e-300);
    result.theta = theta;
    result.iterations = it + 1;
    const Eigen::VectorXd r = Ys * theta - ms;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = std::abs(r(i));
      w(i) = a <= options.huber_k ? 1.0 : options.huber_k / a;
    }
    if (change < options.tolerance) break;
  }
  result.rank = static_cast<int>(qr.rank());
  const Eigen::VectorXd r = Ys * result.theta - ms;
  result.outlier_fraction =
      static_cast<double>((r.array().abs() > options.huber_k).count()) / static_cast<double>(n);
  const Eigen::MatrixXd Yw = w.cwiseSqrt().asDiagonal() * Ys;
  const Eigen::MatrixXd info = Yw.transpose() * Yw;
  result.covariance = info.completeOrthogonalDecomposition().pseudoInverse();
  return result;
}

}  // namespace mrqp::estimation
