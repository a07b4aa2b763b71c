#include "case_study.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrqp::case_study {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kT0 = std::sqrt(6.0) - 2.0;  // end of the saturated phase, eq. 40

}  // namespace

double desiredAcceleration(const BoxState& s) { return -2.0 * s.qd - s.q + 1.0; }

double Decision::newtonViolation() const { return std::max(std::abs(f13 + f31), std::abs(f23 + f32)); }

CaseStudy::CaseStudy() : problem_(7, 6, 0), solver_(7, 6, 0) { solver_.settings().warm_start = true; }

// Variables x = (q̈11, q̈21, q̈31, τ11, τ21, f13, f23).
//   EoM box (eq. 29):            q̈31 − f13 − f23 = 0
//   EoM robots (eq. 30, eq. 13):  τ11 − f13 = 0,  τ21 − f23 = 0   (their f⁺ = −f13, −f23)
//   contact kinematics (eq. 15):  q̈11 − q̈31 = 0,  q̈21 − q̈31 = 0
//   cost: (q̈31 − g̈d)² + ε‖(τ, f)‖²;  bounds |τ11|, |τ21| ≤ 1/2
Decision CaseStudy::multiRobot(const BoxState& s) {
  qp::QpProblem& p = problem_;
  p.resize(7, 5, 0);
  p.clear();
  const double gd = desiredAcceleration(s);
  p.H()(2, 2) = 2.0;
  p.g()(2) = -2.0 * gd;
  for (int k = 3; k < 7; ++k) p.H()(k, k) = 2.0 * kForceWeight;
  p.A()(0, 2) = 1.0, p.A()(0, 5) = -1.0, p.A()(0, 6) = -1.0;
  p.A()(1, 3) = 1.0, p.A()(1, 5) = -1.0;
  p.A()(2, 4) = 1.0, p.A()(2, 6) = -1.0;
  p.A()(3, 0) = 1.0, p.A()(3, 2) = -1.0;
  p.A()(4, 1) = 1.0, p.A()(4, 2) = -1.0;
  p.xl().setConstant(-kInf);
  p.xu().setConstant(kInf);
  p.xl()(3) = p.xl()(4) = -kTauMax;
  p.xu()(3) = p.xu()(4) = kTauMax;
  Decision d;
  d.ok = solver_.solve(p) == qp::QpStatus::Optimal;
  const auto x = solver_.x();
  d.qdd31 = x(2);
  d.tau11 = x(3);
  d.tau21 = x(4);
  d.f13 = x(5);
  d.f23 = x(6);
  d.f31 = -x(5);  // the same variable, applied with the opposite sign on the robot
  d.f32 = -x(6);
  return d;
}

// QP1: robot 1 alone imposes the box motion: x = (q̈11, τ11), q̈11 = τ11 (box EoM with robot 1's
// force only, contact kinematics), |τ11| ≤ 1/2, cost (q̈11 − g̈'d)². QP3 then has no freedom left:
// q̈31 = q̈11 and f23 = q̈31 − f13 = 0; QP2 follows the box with τ21 = f23 = 0.
Decision CaseStudy::sequential(const BoxState& s) {
  qp::QpProblem& p = problem_;
  p.resize(2, 1, 0);
  p.clear();
  const double gd = desiredAcceleration(s);  // g'_1 = q11 = q31 in contact
  p.H()(0, 0) = 2.0;
  p.g()(0) = -2.0 * gd;
  p.H()(1, 1) = 2.0 * kForceWeight;
  p.A()(0, 0) = 1.0, p.A()(0, 1) = -1.0;
  p.xl()(0) = -kInf, p.xu()(0) = kInf;
  p.xl()(1) = -kTauMax, p.xu()(1) = kTauMax;
  Decision d;
  d.ok = solver_.solve(p) == qp::QpStatus::Optimal;
  const double qdd11 = solver_.x()(0), tau11 = solver_.x()(1);
  // QP3: box follows robot 1, with robot 1's force
  d.qdd31 = qdd11;
  d.f13 = tau11;
  d.f23 = d.qdd31 - d.f13;
  // QP2: robot 2 in contact follows the box, applying what QP3 assigned to it
  d.tau11 = tau11;
  d.tau21 = d.f23;
  d.f31 = -tau11;
  d.f32 = -d.tau21;
  return d;
}

// Each QP alone (eq. 31–33), with force minimisation to pick one of its many solutions:
//   QP1: x = (q̈11, f31, τ11): min (q̈11 − g̈'d)² s.t. f31 + τ11 = 0, |τ11| ≤ 1/2   (QP2 alike)
//   QP3: x = (q̈31, f13, f23): min (q̈31 − g̈d)² s.t. q̈31 = f13 + f23
Decision CaseStudy::parallel(const BoxState& s) {
  const double gd = desiredAcceleration(s);
  Decision d;
  d.ok = true;
  double robot[2][2];  // (f3i, τi1) for i = 1, 2
  for (int i = 0; i < 2; ++i) {
    qp::QpProblem& p = problem_;
    p.resize(3, 1, 0);
    p.clear();
    p.H()(0, 0) = 2.0;
    p.g()(0) = -2.0 * gd;
    p.H()(1, 1) = p.H()(2, 2) = 2.0 * kForceWeight;
    p.A()(0, 1) = 1.0, p.A()(0, 2) = 1.0;
    p.xl().setConstant(-kInf);
    p.xu().setConstant(kInf);
    p.xl()(2) = -kTauMax, p.xu()(2) = kTauMax;
    d.ok = d.ok && solver_.solve(p) == qp::QpStatus::Optimal;
    robot[i][0] = solver_.x()(1);
    robot[i][1] = solver_.x()(2);
  }
  qp::QpProblem& p = problem_;
  p.resize(3, 1, 0);
  p.clear();
  p.H()(0, 0) = 2.0;
  p.g()(0) = -2.0 * gd;
  p.H()(1, 1) = p.H()(2, 2) = 2.0 * kForceWeight;
  p.A()(0, 0) = 1.0, p.A()(0, 1) = -1.0, p.A()(0, 2) = -1.0;
  p.xl().setConstant(-kInf);
  p.xu().setConstant(kInf);
  d.ok = d.ok && solver_.solve(p) == qp::QpStatus::Optimal;
  d.qdd31 = solver_.x()(0);
  d.f13 = solver_.x()(1);
  d.f23 = solver_.x()(2);
  d.f31 = robot[0][0];
  d.tau11 = robot[0][1];
  d.f32 = robot[1][0];
  d.tau21 = robot[1][1];
  return d;
}

double analyticMultiRobotPosition(double t) { return 1.0 - (1.0 + t) * std::exp(-t); }
double analyticMultiRobotAcceleration(double t) { return (1.0 - t) * std::exp(-t); }

double analyticSequentialPosition(double t) {
  if (t <= kT0) return 0.25 * t * t;
  return 1.0 + 0.5 * std::exp(-t - 2.0 + std::sqrt(6.0)) *
                   (11.0 - 5.0 * std::sqrt(6.0) + t * (1.0 - std::sqrt(6.0)));
}

double analyticSequentialAcceleration(double t) {
  if (t <= kT0) return 0.5;
  return 0.5 * std::exp(-t - 2.0 + std::sqrt(6.0)) *
         (9.0 - 3.0 * std::sqrt(6.0) + t * (1.0 - std::sqrt(6.0)));
}

}  // namespace mrqp::case_study
