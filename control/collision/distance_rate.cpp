// The curvature part of the distance's second derivative; see distance_rate.hpp.
#include "collision/distance_rate.hpp"

#include <Eigen/LU>

#include <array>
#include <cmath>

namespace mrqp::collision {

double distanceCurvature(const DistanceResult& r, double radius_a, double radius_b, const RigidMotion& ma,
                         const RigidMotion& mb, double step) noexcept {
  const int k = r.simplex_size;
  if (r.penetrating || k < 1 || k > 3) return 0.0;
  const auto i0 = std::size_t{0};
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, 3> w, wd;
  for (int i = 0; i < k; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    w[ui] = r.simplex_b[ui] - r.simplex_a[ui];
    wd[ui] = mb.velocityOf(r.simplex_b[ui]) - ma.velocityOf(r.simplex_a[ui]);
    x += r.simplex_lambda[ui] * w[ui];
  }
  const double L = x.norm();
  if (!(L > 0.0)) return 0.0;
  const Eigen::Vector3d n = x / L;
  // μ̇ from EᵀE μ̇ = −Ėᵀx − Eᵀ(ẇ_0 + Ė μ), m = k − 1 ≤ 2.
  const int m = k - 1;
  Eigen::Vector3d xd = wd[i0];
  std::array<double, 3> lambda_dot{0.0, 0.0, 0.0};
  if (m > 0) {
    Eigen::Matrix<double, 3, 2> E = Eigen::Matrix<double, 3, 2>::Zero(),
                                Ed = Eigen::Matrix<double, 3, 2>::Zero();
    Eigen::Vector2d mu = Eigen::Vector2d::Zero();
    for (int j = 1; j < k; ++j) {
      const auto uj = static_cast<std::size_t>(j);
      E.col(j - 1) = w[uj] - w[i0];
      Ed.col(j - 1) = wd[uj] - wd[i0];
      mu(j - 1) = r.simplex_lambda[uj];
    }
    const Eigen::Vector3d base = wd[i0] + Ed * mu;  // ẇ_0 + Ė μ (the unused column is zero)
    Eigen::Matrix2d G = Eigen::Matrix2d::Identity();
    G.topLeftCorner(m, m) = E.leftCols(m).transpose() * E.leftCols(m);
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    rhs.head(m) = -(Ed.leftCols(m).transpose() * x) - E.leftCols(m).transpose() * base;
    const double det = G.determinant();
    const double scale = G.diagonal().head(m).maxCoeff();
    if (!(std::abs(det) > 1e-12 * std::pow(scale, m))) return 0.0;  // a degenerate face: no rate
    Eigen::Vector2d mu_dot = G.inverse() * rhs;
    if (step > 0.0) {
      // Keep every barycentric coordinate within [0, 1] over the step (distance_rate.hpp).
      const double rate0 = -mu_dot.head(m).sum();
      double scale_dot = 1.0;
      for (int i = 0; i < k; ++i) {
        const double ld = i == 0 ? rate0 : mu_dot(i - 1);
        const double li = r.simplex_lambda[static_cast<std::size_t>(i)];
        const double room = ld < 0.0 ? li : 1.0 - li;
        const double travel = std::abs(ld) * step;
        if (travel > std::max(room, 0.0)) scale_dot = std::min(scale_dot, std::max(room, 0.0) / travel);
      }
      mu_dot *= scale_dot;
    }
    double sum = 0.0;
    for (int j = 1; j < k; ++j) {
      lambda_dot[static_cast<std::size_t>(j)] = mu_dot(j - 1);
      sum += mu_dot(j - 1);
    }
    lambda_dot[i0] = -sum;
    xd = E * mu_dot + base;
  }
  double c = (xd.squaredNorm() - n.dot(xd) * n.dot(xd)) / L;
  for (int i = 0; i < k; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    c += 2.0 * lambda_dot[ui] * n.dot(wd[ui]);
  }
  const double wa = ma.omega.dot(n), wb = mb.omega.dot(n);
  c += radius_a * (wa * wa - ma.omega.squaredNorm()) + radius_b * (wb * wb - mb.omega.squaredNorm());
  return c;
}

}  // namespace mrqp::collision
