// ParameterKalman (paper 1, eq. 52–59) against the batch solution it must equal, and its
// statistical consistency under noise.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <random>

#include "estimation/parameter_kalman.hpp"

using mrqp::estimation::ParameterKalman;

namespace {

Eigen::MatrixXd randomMatrix(std::mt19937& rng, int r, int c) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd m(r, c);
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < c; ++j) m(i, j) = n(rng);
  return m;
}

}  // namespace

TEST_CASE("With Q = 0 the filter equals the batch regularised least-squares solution",
          "[estimation][kalman]") {
  // With a random-walk model and Q = 0 the posterior after k updates is the Gaussian posterior of
  // the stacked linear model: P⁻¹ = P0⁻¹ + Σ YᵀR⁻¹Y, φ = P (P0⁻¹ φ0 + Σ YᵀR⁻¹μ).
  std::mt19937 rng(7);
  const int p = 7, m = 3, steps = 40;
  ParameterKalman kf(p, m);
  const Eigen::VectorXd phi0 = randomMatrix(rng, p, 1);
  const Eigen::MatrixXd B = randomMatrix(rng, p, p);
  const Eigen::MatrixXd P0 = B * B.transpose() + Eigen::MatrixXd::Identity(p, p);
  const Eigen::MatrixXd C = randomMatrix(rng, m, m);
  const Eigen::MatrixXd R = 0.1 * C * C.transpose() + 0.05 * Eigen::MatrixXd::Identity(m, m);
  kf.reset(phi0, P0);
  const Eigen::MatrixXd Rinv = R.inverse();
  Eigen::MatrixXd info = P0.inverse();
  Eigen::VectorXd rhs = info * phi0;
  for (int k = 0; k < steps; ++k) {
    const Eigen::MatrixXd Y = randomMatrix(rng, m, p);
    const Eigen::VectorXd mu = randomMatrix(rng, m, 1);
    REQUIRE(kf.update(Y, mu, R));
    info += Y.transpose() * Rinv * Y;
    rhs += Y.transpose() * Rinv * mu;
  }
  const Eigen::MatrixXd P = info.inverse();
  const Eigen::VectorXd phi = P * rhs;
  CHECK((kf.estimate() - phi).norm() <= 1e-9 * std::max(1.0, phi.norm()));
  CHECK((kf.covariance() - P).norm() <= 1e-9 * P.norm());
  CHECK(kf.covariance().isApprox(kf.covariance().transpose(), 0.0));
}

TEST_CASE("Noise-free observations recover the parameters exactly", "[estimation][kalman]") {
  std::mt19937 rng(11);
  const int p = 10, m = 6;
  const Eigen::VectorXd truth = randomMatrix(rng, p, 1);
  ParameterKalman kf(p, m);
  kf.reset(Eigen::VectorXd::Zero(p), 1e8 * Eigen::MatrixXd::Identity(p, p));
  const Eigen::MatrixXd R = 1e-6 * Eigen::MatrixXd::Identity(m, m);
  for (int k = 0; k < 50; ++k) {
    const Eigen::MatrixXd Y = randomMatrix(rng, m, p);
    REQUIRE(kf.update(Y, Y * truth, R));
  }
  CHECK((kf.estimate() - truth).cwiseAbs().maxCoeff() <= 1e-9);
}

TEST_CASE("Under noise the true parameters lie within 3 sigma of the estimate in at least 95 % of seeds",
          "[estimation][kalman]") {
  const int p = 10, m = 6, seeds = 200;
  int inside = 0;
  double nis_sum = 0.0;
  int nis_count = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(1000 + seed));
    const Eigen::VectorXd truth = randomMatrix(rng, p, 1);
    const Eigen::VectorXd sd = (Eigen::VectorXd::Random(m).array() * 0.5 + 1.0).matrix() * 0.2;
    const Eigen::MatrixXd R = sd.cwiseAbs2().asDiagonal();
    ParameterKalman kf(p, m);
    kf.reset(Eigen::VectorXd::Zero(p), 100.0 * Eigen::MatrixXd::Identity(p, p));
    std::normal_distribution<double> n(0.0, 1.0);
    for (int k = 0; k < 30; ++k) {
      const Eigen::MatrixXd Y = randomMatrix(rng, m, p);
      Eigen::VectorXd noise(m);
      for (int i = 0; i < m; ++i) noise(i) = sd(i) * n(rng);
      REQUIRE(kf.update(Y, Y * truth + noise, R));
      if (k >= 10) {
        nis_sum += kf.lastNis();
        ++nis_count;
      }
    }
    const Eigen::VectorXd sigma = kf.covariance().diagonal().cwiseSqrt();
    if (((kf.estimate() - truth).cwiseAbs().array() <= 3.0 * sigma.array()).all()) ++inside;
  }
  CHECK(inside >= 95 * seeds / 100);
  // The normalised innovation squared averages m for a consistent filter.
  CHECK(nis_sum / nis_count == Approx(m).epsilon(0.1));
}

TEST_CASE("A rejected update leaves the state unchanged", "[estimation][kalman]") {
  ParameterKalman kf(2, 1);
  kf.reset(Eigen::Vector2d(1.0, 2.0), Eigen::Matrix2d::Identity());
  const Eigen::MatrixXd Y = Eigen::RowVector2d(1.0, 0.0);
  Eigen::VectorXd mu(1);
  mu << std::nan("");
  CHECK_FALSE(kf.update(Y, mu, Eigen::MatrixXd::Identity(1, 1)));
  mu << 1.0;
  CHECK_FALSE(kf.update(Y, mu, -Eigen::MatrixXd::Identity(1, 1) * 10.0));  // S not positive definite
  CHECK_FALSE(kf.update(Eigen::MatrixXd::Ones(2, 2), mu, Eigen::MatrixXd::Identity(1, 1)));  // wrong size
  CHECK(kf.estimate() == Eigen::Vector2d(1.0, 2.0));
  CHECK(kf.covariance() == Eigen::Matrix2d::Identity());
}

TEST_CASE("An unobserved direction keeps its variance growing by Q only", "[estimation][kalman]") {
  ParameterKalman kf(2, 1);
  kf.reset(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());
  kf.setProcessNoise(Eigen::Vector2d(1e-4, 1e-4));
  const Eigen::MatrixXd Y = Eigen::RowVector2d(1.0, 0.0);
  Eigen::VectorXd mu(1);
  mu << 3.0;
  for (int k = 0; k < 100; ++k) REQUIRE(kf.update(Y, mu, 0.01 * Eigen::MatrixXd::Identity(1, 1)));
  CHECK(kf.covariance()(1, 1) == Approx(1.0 + 100 * 1e-4).epsilon(1e-12));
  CHECK(kf.covariance()(0, 1) == Approx(0.0).margin(1e-15));
  CHECK(kf.estimate()(0) == Approx(3.0).epsilon(1e-6));
  CHECK(kf.estimate()(1) == 0.0);
}
