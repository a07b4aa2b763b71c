#include "qp/qp_random.hpp"

#include <cmath>
#include <limits>

namespace mrqp::qp {

namespace {
Eigen::MatrixXd gaussian(int rows, int cols, std::mt19937_64& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd M(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) M(i, j) = N(rng);
  return M;
}
}  // namespace

bool generateRandomQp(const RandomQpSpec& spec, std::mt19937_64& rng, QpProblem& problem) {
  if (!problem.resize(spec.n, spec.me, spec.mi)) return false;
  const int n = spec.n;
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const int rank = spec.hessian_rank < 0 ? n : spec.hessian_rank;
  const Eigen::MatrixXd M = gaussian(rank, n, rng);
  Eigen::MatrixXd H = M.transpose() * M / std::max(1, n);
  if (spec.hessian_rank < 0) H.diagonal().array() += spec.hessian_shift;
  problem.H() = H;
  Eigen::VectorXd x0(n);
  for (int j = 0; j < n; ++j) x0(j) = 2.0 * U(rng) - 1.0;
  const double hnorm = n > 0 ? std::max(1e-3, H.diagonal().maxCoeff()) : 1.0;
  problem.g() = gaussian(n, 1, rng) * spec.gradient_scale * hnorm;
  problem.A() = gaussian(spec.me, n, rng);
  problem.b() = problem.A() * x0;
  problem.C() = gaussian(spec.mi, n, rng);
  const Eigen::VectorXd cx = problem.C() * x0;
  for (int i = 0; i < spec.mi; ++i) {
    const double scale = problem.C().row(i).norm() / std::sqrt(static_cast<double>(std::max(1, n)));
    double lo = cx(i) - (0.1 + U(rng)) * scale;
    double up = cx(i) + (0.1 + U(rng)) * scale;
    const double pick = U(rng);
    if (pick < spec.one_sided)
      lo = -inf;
    else if (pick < 2.0 * spec.one_sided)
      up = inf;
    problem.l()(i) = lo;
    problem.u()(i) = up;
  }
  for (int j = 0; j < n; ++j) {
    problem.xl()(j) = spec.bounds ? x0(j) - (0.1 + U(rng)) : -inf;
    problem.xu()(j) = spec.bounds ? x0(j) + (0.1 + U(rng)) : inf;
  }
  return true;
}

void perturbQp(double eps, std::mt19937_64& rng, QpProblem& problem) {
  std::normal_distribution<double> N(0.0, 1.0);
  auto wiggle = [&](double v, double ref) {
    return std::isfinite(v) ? v + eps * N(rng) * std::max(1.0, std::abs(ref)) : v;
  };
  const int n = problem.n();
  const double gnorm = problem.g().lpNorm<Eigen::Infinity>();
  for (int j = 0; j < n; ++j) problem.g()(j) = wiggle(problem.g()(j), gnorm);
  // a symmetric perturbation of H that keeps it positive semi-definite: H + eps·diag(|H_jj|)
  for (int j = 0; j < n; ++j) problem.H()(j, j) += eps * std::abs(problem.H()(j, j)) * std::abs(N(rng));
  // shifts of the bounds much smaller than the margin (≥ 0.1) of the generator's feasible point
  for (int i = 0; i < problem.mi(); ++i) {
    problem.l()(i) = wiggle(problem.l()(i), 1.0);
    problem.u()(i) = wiggle(problem.u()(i), 1.0);
  }
  for (int j = 0; j < n; ++j) {
    problem.xl()(j) = wiggle(problem.xl()(j), 1.0);
    problem.xu()(j) = wiggle(problem.xu()(j), 1.0);
  }
}

}  // namespace mrqp::qp
