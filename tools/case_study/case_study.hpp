// The analytic two-robots-one-box case study (multi-robot QP paper, Sec. II-C, eq. 27–44):
// two massless robots push a unit-mass box sliding without friction from q31 = 0 to q31 = 1
// under a critically damped task, actuation |τ11|, |τ21| ≤ 1/2.
//
// Only the sliding direction is modelled: the normal direction is at rest and decoupled. Forces are
// written once, as in eq. 2–13: f13 and f23 are the forces robots 1 and 2 apply on the box (F⁻ of
// the box); the robots' EoMs receive −f13 and −f23 (their f⁺), so Newton's third law holds by
// construction in the multi-robot QP.
#pragma once

#include "qp/qp_problem.hpp"
#include "qp/qp_solver.hpp"

namespace mrqp::case_study {

struct BoxState {
  double q = 0.0;   ///< q31
  double qd = 0.0;  ///< q̇31
};

/// Desired task acceleration, eq. 27–28: g̈d = −2 ġ − g + 1.
double desiredAcceleration(const BoxState& s);

/// What one evaluation of a control scheme decided at a state.
struct Decision {
  bool ok = false;
  double qdd31 = 0.0;  ///< box acceleration
  double tau11 = 0.0, tau21 = 0.0;
  double f13 = 0.0, f23 = 0.0;     ///< forces on the box, as the box's QP sees them
  double f31 = 0.0, f32 = 0.0;     ///< forces on the robots, as the robots' QPs see them
  double newtonViolation() const;  ///< max(|f13 + f31|, |f23 + f32|)
};

/// The QPs of the study, each a small problem for mrqp's solver.
class CaseStudy {
 public:
  CaseStudy();
  /// QPall, eq. 42: one QP over (q̈11, q̈21, q̈31, τ11, τ21, f13, f23).
  Decision multiRobot(const BoxState& s);
  /// Sequential decoupled QP1 → QP3 → QP2, eq. 39–41 (robot 1 imposes the motion, robot 2 follows).
  Decision sequential(const BoxState& s);
  /// Parallel decoupled QP1, QP2, QP3, eq. 31–33, each unaware of the others.
  Decision parallel(const BoxState& s);

 private:
  static constexpr double kTauMax = 0.5;
  static constexpr double kForceWeight = 1e-8;  ///< force minimisation, makes each QP strictly convex
  qp::QpProblem problem_;
  qp::QpSolver solver_;
};

/// Closed forms: eq. 43–44 (multi-robot QP) and eq. 40–41 (QP1 → QP3 → QP2).
double analyticMultiRobotPosition(double t);
double analyticMultiRobotAcceleration(double t);
double analyticSequentialPosition(double t);
double analyticSequentialAcceleration(double t);

/// One classical Runge–Kutta step of the box under a scheme's acceleration law.
template <class Law>
bool rk4Step(BoxState& s, double dt, Law&& law) {
  auto acc = [&](const BoxState& x, double& a) {
    const Decision d = law(x);
    a = d.qdd31;
    return d.ok;
  };
  double a1, a2, a3, a4;
  const BoxState s1 = s;
  if (!acc(s1, a1)) return false;
  const BoxState s2{s.q + 0.5 * dt * s1.qd, s.qd + 0.5 * dt * a1};
  if (!acc(s2, a2)) return false;
  const BoxState s3{s.q + 0.5 * dt * s2.qd, s.qd + 0.5 * dt * a2};
  if (!acc(s3, a3)) return false;
  const BoxState s4{s.q + dt * s3.qd, s.qd + dt * a3};
  if (!acc(s4, a4)) return false;
  s.q += dt / 6.0 * (s1.qd + 2 * s2.qd + 2 * s3.qd + s4.qd);
  s.qd += dt / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
  return true;
}

}  // namespace mrqp::case_study
