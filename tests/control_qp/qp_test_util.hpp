// Independent checks for the QP solver tests: the KKT conditions evaluated from the problem data
// and the returned (x, y, λ, μ), and a brute-force solver that enumerates every active set of a
// tiny problem.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "qp/qp_problem.hpp"
#include "qp/qp_solver.hpp"

namespace qptest {

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;

struct Kkt {
  double stationarity = 0;     // ‖Hx + g + Aᵀy + Cᵀλ + μ‖∞ / scale
  double primal = 0;           // max violation / max(1, |bound|)
  double dual = 0;             // multiplier of the wrong sign or on an infinite side (scaled)
  double complementarity = 0;  // max |multiplier|·distance to its bound (scaled)
  double worst() const { return std::max({stationarity, primal, dual, complementarity}); }
};

inline Kkt kktErrors(const QpProblem& p, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                     const Eigen::VectorXd& lam, const Eigen::VectorXd& mu) {
  Kkt k;
  const Eigen::MatrixXd H = 0.5 * (p.H() + p.H().transpose());
  const Eigen::VectorXd hx = H * x, aty = p.A().transpose() * y, ctl = p.C().transpose() * lam;
  const Eigen::VectorXd res = hx + p.g() + aty + ctl + mu;
  auto inf = [](const Eigen::VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; };
  const double scale = std::max({1.0, inf(hx), inf(p.g()), inf(aty), inf(ctl), inf(mu)});
  k.stationarity = inf(res) / scale;
  const double mscale = std::max({1.0, inf(y), inf(lam), inf(mu)});
  auto side = [&](double value, double lo, double up, double m) {
    const double viol = std::max({0.0, lo - value, value - up});
    k.primal = std::max(k.primal, viol / std::max({1.0, std::isfinite(lo) ? std::abs(lo) : 0.0,
                                                   std::isfinite(up) ? std::abs(up) : 0.0}));
    if (m < 0) {  // lower side
      if (!std::isfinite(lo))
        k.dual = std::max(k.dual, -m / mscale);
      else
        k.complementarity =
            std::max(k.complementarity, -m * std::abs(value - lo) / mscale / std::max(1.0, std::abs(lo)));
    }
    if (m > 0) {
      if (!std::isfinite(up))
        k.dual = std::max(k.dual, m / mscale);
      else
        k.complementarity =
            std::max(k.complementarity, m * std::abs(up - value) / mscale / std::max(1.0, std::abs(up)));
    }
  };
  const Eigen::VectorXd ax = p.A() * x, cx = p.C() * x;
  for (int i = 0; i < p.me(); ++i) side(ax(i), p.b()(i), p.b()(i), 0.0);
  for (int i = 0; i < p.mi(); ++i) side(cx(i), p.l()(i), p.u()(i), lam(i));
  for (int j = 0; j < p.n(); ++j) side(x(j), p.xl()(j), p.xu()(j), mu(j));
  return k;
}

inline Kkt kktErrors(const QpProblem& p, const QpSolver& s) {
  return kktErrors(p, s.x(), s.equalityMultipliers(), s.inequalityMultipliers(), s.boundMultipliers());
}

/// Brute force over every active set of a tiny problem (strictly convex H). Returns false if no
/// active set gives a feasible point, i.e. the problem is infeasible.
inline bool bruteForce(const QpProblem& p, Eigen::VectorXd& best_x, double& best_f, double tol = 1e-9) {
  const int n = p.n(), me = p.me(), mi = p.mi();
  const int m = mi + n;  // inequality rows then bounds, each inactive / lower / upper
  const Eigen::MatrixXd H = 0.5 * (p.H() + p.H().transpose());
  best_f = std::numeric_limits<double>::infinity();
  std::vector<int> state(static_cast<std::size_t>(m), 0);
  long total = 1;
  for (int k = 0; k < m; ++k) total *= 3;
  for (long code = 0; code < total; ++code) {
    long c = code;
    bool skip = false;
    std::vector<Eigen::VectorXd> rows;
    std::vector<double> rhs;
    for (int i = 0; i < me; ++i) {
      rows.push_back(p.A().row(i).transpose());
      rhs.push_back(p.b()(i));
    }
    for (int k = 0; k < m && !skip; ++k) {
      const int s = static_cast<int>(c % 3);
      c /= 3;
      if (s == 0) continue;
      Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
      double lo, up;
      if (k < mi) {
        row = p.C().row(k).transpose();
        lo = p.l()(k);
        up = p.u()(k);
      } else {
        row(k - mi) = 1.0;
        lo = p.xl()(k - mi);
        up = p.xu()(k - mi);
      }
      const double v = s == 1 ? lo : up;
      if (!std::isfinite(v)) skip = true;
      if (s == 2 && lo == up) skip = true;  // same equation twice
      rows.push_back(row);
      rhs.push_back(v);
    }
    if (skip) continue;
    const int na = static_cast<int>(rows.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + na, n + na);
    Eigen::VectorXd r(n + na);
    K.topLeftCorner(n, n) = H;
    r.head(n) = -p.g();
    for (int a = 0; a < na; ++a) {
      K.row(n + a).head(n) = rows[static_cast<std::size_t>(a)].transpose();
      K.col(n + a).head(n) = rows[static_cast<std::size_t>(a)];
      r(n + a) = rhs[static_cast<std::size_t>(a)];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (lu.rank() < n + na) continue;
    const Eigen::VectorXd sol = lu.solve(r);
    const Eigen::VectorXd x = sol.head(n);
    bool feasible = true;
    const Eigen::VectorXd ax = p.A() * x, cx = p.C() * x;
    for (int i = 0; i < me; ++i)
      feasible &= std::abs(ax(i) - p.b()(i)) <= tol * std::max(1.0, std::abs(p.b()(i)));
    for (int i = 0; i < mi; ++i)
      feasible &= cx(i) >= p.l()(i) - tol * std::max(1.0, std::abs(p.l()(i))) &&
                  cx(i) <= p.u()(i) + tol * std::max(1.0, std::abs(p.u()(i)));
    for (int j = 0; j < n; ++j)
      feasible &= x(j) >= p.xl()(j) - tol * std::max(1.0, std::abs(p.xl()(j))) &&
                  x(j) <= p.xu()(j) + tol * std::max(1.0, std::abs(p.xu()(j)));
    if (!feasible) continue;
    const double f = 0.5 * x.dot(H * x) + p.g().dot(x);
    if (f < best_f) {
      best_f = f;
      best_x = x;
    }
  }
  return std::isfinite(best_f);
}

}  // namespace qptest
