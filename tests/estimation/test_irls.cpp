// IRLS (the offline batch method) against ordinary least squares and under outliers.
#include <catch2/catch.hpp>

#include <Eigen/QR>
#include <random>

#include "estimation/irls.hpp"

using mrqp::estimation::irlsEstimate;

TEST_CASE("Without outliers IRLS is the weighted least-squares solution", "[estimation][irls]") {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  const int N = 300, p = 5;
  Eigen::MatrixXd Y(N, p);
  Eigen::VectorXd mu(N), sigma(N);
  const Eigen::VectorXd truth = Eigen::VectorXd::LinSpaced(p, -1.0, 2.0);
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < p; ++j) Y(i, j) = n(rng);
    sigma(i) = 0.01;
    mu(i) = Y.row(i).dot(truth) + 0.01 * std::max(-1.0, std::min(1.0, n(rng)));  // all inside ±1.345 σ
  }
  const auto r = irlsEstimate(Y, mu, sigma);
  const Eigen::VectorXd ls = Y.colPivHouseholderQr().solve(mu);
  CHECK((r.theta - ls).norm() <= 1e-10);
  CHECK(r.rank == p);
  CHECK(r.outlier_fraction == 0.0);
}

TEST_CASE("IRLS resists gross outliers that pull least squares away", "[estimation][irls]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  const int N = 400, p = 4;
  Eigen::MatrixXd Y(N, p);
  Eigen::VectorXd mu(N), sigma = Eigen::VectorXd::Constant(N, 0.05);
  const Eigen::VectorXd truth(Eigen::Vector4d(0.941, 0.02, -0.01, 0.05));
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < p; ++j) Y(i, j) = n(rng);
    mu(i) = Y.row(i).dot(truth) + 0.05 * n(rng) + (i % 20 == 0 ? 30.0 : 0.0);  // 5 % outliers
  }
  const auto r = irlsEstimate(Y, mu, sigma);
  const Eigen::VectorXd ls = Y.colPivHouseholderQr().solve(mu);
  CHECK((r.theta - truth).norm() < 0.02);
  CHECK((ls - truth).norm() > 5.0 * (r.theta - truth).norm());
  CHECK(r.outlier_fraction >= 0.05);
}

TEST_CASE("IRLS reports a rank-deficient regressor and rejects bad input", "[estimation][irls]") {
  Eigen::MatrixXd Y(3, 2);
  Y << 1, 2, 2, 4, 3, 6;  // second column = 2 × first
  const Eigen::VectorXd mu = Eigen::Vector3d(1, 2, 3), sigma = Eigen::Vector3d::Ones();
  CHECK(irlsEstimate(Y, mu, sigma).rank == 1);
  CHECK_THROWS_AS(irlsEstimate(Y, mu, -sigma), std::invalid_argument);
  CHECK_THROWS_AS(irlsEstimate(Y, Eigen::Vector2d(1, 2), Eigen::Vector2d(1, 1)), std::invalid_argument);
}
