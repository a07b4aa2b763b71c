// Joint inequality kept by a velocity damper (eq. 21, 24); see joint_inequality.hpp.
#include "problem/constraints/joint_inequality.hpp"

#include <algorithm>
#include <cmath>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

JointInequality::JointInequality(const Term* terms, int count, double upper, double interaction,
                                 double security, double damping)
    : count_(count), upper_(upper), interaction_(interaction), security_(security), damping_(damping) {
  for (int k = 0; k < std::min(count, kMaxTerms); ++k) terms_[static_cast<std::size_t>(k)] = terms[k];
}

const char* JointInequality::check(const MultiRobotProblem& p) const noexcept {
  if (count_ < 1 || count_ > kMaxTerms || !(interaction_ > security_) || !(damping_ > 0.0) ||
      !std::isfinite(upper_)) {
    return "a joint inequality needs 1 to 4 terms, interaction > security and damping > 0";
  }
  for (int k = 0; k < count_; ++k) {
    const Term& t = term(k);
    if (t.entity < 0 || t.entity >= p.entityCount() || t.joint < p.entity(t.entity).jointOffset() ||
        t.joint >= p.entity(t.entity).nv()) {
      return "a joint inequality names a joint that does not exist";
    }
  }
  return nullptr;
}

void JointInequality::update(const MultiRobotProblem& p, ConstraintRows& out) noexcept {
  double s = upper_, sdot = 0.0;
  for (int k = 0; k < count_; ++k) {
    const Term& t = term(k);
    const Entity& e = p.entity(t.entity);
    s -= t.coeff * e.q()(e.qIndexOfV(t.joint));
    sdot -= t.coeff * e.v()(t.joint);
  }
  slack_ = s;
  if (s >= interaction_) return;
  for (int k = 0; k < count_; ++k) {
    const Term& t = term(k);
    out.C(0, p.velocityOffset(t.entity) + t.joint) -= p.settings().dt * t.coeff;
  }
  out.l(0) = -damping_ * (s - security_) / (interaction_ - security_) - sdot;
}

}  // namespace mrqp::problem
