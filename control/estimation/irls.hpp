// Batch estimation of linear parameters by iteratively reweighted least squares (the paper's
// offline method, Sec. IV): minimise Σᵢ ρ(rᵢ / σᵢ) over the stacked rows rᵢ = Yᵢ θ − μᵢ with
// Huber's ρ (quadratic inside ±k, linear outside), each row scaled by its noise σᵢ. Each
// iteration solves a weighted least-squares problem by a rank-revealing QR; unidentifiable
// directions are reported, not invented. Offline: allocates.
#pragma once

#include <Eigen/Core>

namespace mrqp::estimation {

struct IrlsOptions {
  double huber_k = 1.345;  ///< in units of σ (95 % efficiency under Gaussian noise)
  int max_iterations = 50;
  double tolerance = 1e-10;  ///< relative change of θ that ends the iterations
};

struct IrlsResult {
  Eigen::VectorXd theta;
  Eigen::MatrixXd covariance;  ///< (Yᵀ W Y)⁻¹ at the solution (σ-scaled rows)
  int rank = 0;                ///< numerical rank of the weighted regressor
  int iterations = 0;
  double outlier_fraction = 0.0;  ///< rows beyond ±k σ at the solution
};

/// Y: N × p stacked regressors, mu: N observations, sigma: N noise standard deviations (> 0).
IrlsResult irlsEstimate(const Eigen::MatrixXd& Y, const Eigen::VectorXd& mu, const Eigen::VectorXd& sigma,
                        const IrlsOptions& options = {});

}  // namespace mrqp::estimation
