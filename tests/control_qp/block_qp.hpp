// Random QPs shaped like the multi-robot problem's (docs/problem.md), for the tests of the QP
// solver's structured path: a block-diagonal H (mostly 1×1 blocks with weights from 1e-6 to 1e3,
// a few dense blocks like a frame task's), "accelerations" q and "cone coefficients" λ ≥ 0 with a
// gradient that pushes part of λ onto its bound, equality rows that each touch a range of q and a
// range of λ (equations of motion) or q only (no-slip), a fixed variable, an equality row of C,
// and two-sided or one-sided rows of C. A point x0 satisfies every constraint, so the QP is
// feasible. Host-side test helper: allocates.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "qp/qp_problem.hpp"

namespace qptest {

struct BlockQpSpec {
  int nq = 30;          ///< "accelerations": bounded both sides
  int nl = 24;          ///< "cone coefficients": λ ≥ 0
  int me = 12;          ///< rows of A
  int mi = 10;          ///< rows of C (one of them an equality l = u)
  int dense_every = 6;  ///< about one q variable in this many starts a dense block of 2–5
};

/// Fills `p` (resized; must fit its capacity). Returns the feasible point x0.
inline Eigen::VectorXd generateBlockQp(const BlockQpSpec& s, std::mt19937_64& rng, mrqp::qp::QpProblem& p) {
  const int n = s.nq + s.nl;
  p.resize(n, s.me, s.mi);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto pick = [&](int k) { return static_cast<int>(U(rng) * k) % k; };
  const double weights[] = {1e-6, 1e-1, 1e-2, 1.0, 1e3};
  p.H().setZero();
  for (int i = 0; i < s.nq;) {
    int b = pick(s.dense_every) == 0 ? 2 + pick(4) : 1;
    b = std::min(b, s.nq - i);
    const double w = weights[pick(5)];
    Eigen::MatrixXd M(b, b);
    for (int r = 0; r < b; ++r)
      for (int c = 0; c < b; ++c) M(r, c) = N(rng);
    p.H().block(i, i, b, b) = w * (M.transpose() * M / b + Eigen::MatrixXd::Identity(b, b));
    i += b;
  }
  for (int j = s.nq; j < n; ++j) p.H()(j, j) = 1e-4;
  Eigen::VectorXd x0(n);
  for (int j = 0; j < s.nq; ++j) x0(j) = N(rng);
  for (int j = s.nq; j < n; ++j) x0(j) = U(rng);
  for (int j = 0; j < s.nq; ++j) p.g()(j) = 3.0 * N(rng) * std::max(1e-3, p.H()(j, j));
  for (int j = s.nq; j < n; ++j) p.g()(j) = (U(rng) < 0.5 ? 1.0 : -0.2) * U(rng);
  // equality rows: half touch a range of q and a range of λ, half q only
  p.A().setZero();
  for (int i = 0; i < s.me; ++i) {
    const int q0 = pick(s.nq / 2), qn = 2 + pick(s.nq / 2);
    for (int j = q0; j < std::min(s.nq, q0 + qn); ++j) p.A()(i, j) = N(rng);
    if (i % 2 == 0 && s.nl > 0) {
      const int l0 = pick(s.nl), ln = 1 + pick(std::max(1, s.nl / 3));
      for (int j = s.nq + l0; j < std::min(n, s.nq + l0 + ln); ++j) p.A()(i, j) = N(rng);
    }
  }
  p.b() = p.A() * x0;
  p.C().setZero();
  for (int i = 0; i < s.mi; ++i)
    for (int j = 0; j < s.nq; ++j) p.C()(i, j) = U(rng) < 0.3 ? N(rng) : 0.0;
  const Eigen::VectorXd cx = p.C() * x0;
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < s.mi; ++i) {
    p.l()(i) = cx(i) - 0.05 - U(rng);
    p.u()(i) = cx(i) + 0.05 + U(rng);
    if (i % 4 == 1) p.u()(i) = inf;
    if (i % 4 == 2) p.l()(i) = -inf;
  }
  if (s.mi > 0) p.l()(0) = p.u()(0) = cx(0);  // an equality row of C
  for (int j = 0; j < s.nq; ++j) {
    p.xl()(j) = x0(j) - 0.05 - 0.5 * U(rng);
    p.xu()(j) = x0(j) + 0.05 + 0.5 * U(rng);
  }
  if (s.nq > 3) p.xl()(3) = p.xu()(3) = x0(3);  // a fixed variable
  for (int j = s.nq; j < n; ++j) {
    p.xl()(j) = 0.0;
    p.xu()(j) = inf;
  }
  return x0;
}

/// The next QP of a control loop: g moved by about eps (relative), every finite side of a
/// two-sided row or bound moved outwards or inwards by about eps·(distance to x0), at most half of
/// it, so that x0 stays strictly feasible; λ ≥ 0, the fixed variable and the equalities are kept.
inline void perturbBlockQp(double eps, const Eigen::VectorXd& x0, std::mt19937_64& rng,
                           mrqp::qp::QpProblem& p) {
  std::normal_distribution<double> Z(0.0, 1.0);
  auto N = [&](std::mt19937_64& r) { return std::clamp(Z(r), -0.5 / eps, 0.5 / eps); };
  for (int j = 0; j < p.n(); ++j) p.g()(j) += eps * N(rng) * std::max(1e-3, std::abs(p.g()(j)));
  const Eigen::VectorXd cx = p.C() * x0;
  for (int i = 0; i < p.mi(); ++i) {
    if (p.l()(i) == p.u()(i)) continue;
    if (std::isfinite(p.l()(i))) p.l()(i) -= eps * N(rng) * (p.l()(i) - cx(i));
    if (std::isfinite(p.u()(i))) p.u()(i) -= eps * N(rng) * (p.u()(i) - cx(i));
  }
  for (int j = 0; j < p.n(); ++j) {
    if (p.xl()(j) == p.xu()(j) || p.xl()(j) == 0.0) continue;
    if (std::isfinite(p.xl()(j))) p.xl()(j) -= eps * N(rng) * (p.xl()(j) - x0(j));
    if (std::isfinite(p.xu()(j))) p.xu()(j) -= eps * N(rng) * (p.xu()(j) - x0(j));
  }
}

}  // namespace qptest
