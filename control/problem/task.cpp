// The common part of every task: weight, gains, selection, velocity and acceleration references.
#include "problem/task.hpp"

#include <cmath>

namespace mrqp::problem {

Task::Task(int reference_rows)
    : velocity_ref_(Eigen::VectorXd::Zero(reference_rows)),
      acceleration_ref_(Eigen::VectorXd::Zero(reference_rows)) {}

bool Task::setReference(const Eigen::Ref<const Eigen::VectorXd>& velocity,
                        const Eigen::Ref<const Eigen::VectorXd>& acceleration) noexcept {
  if (velocity.size() != velocity_ref_.size() || acceleration.size() != acceleration_ref_.size() ||
      !velocity.allFinite() || !acceleration.allFinite()) {
    return false;
  }
  velocity_ref_ = velocity;
  acceleration_ref_ = acceleration;
  return true;
}

double Task::dampingUsed() const noexcept { return damping_ >= 0.0 ? damping_ : 2.0 * std::sqrt(stiffness_); }

bool Task::setWeight(double w) noexcept {
  if (!(w >= 0.0) || !std::isfinite(w)) return false;
  weight_ = w;
  return true;
}

bool Task::setGains(double k, double d) noexcept {
  if (!(k >= 0.0) || !std::isfinite(k) || !std::isfinite(d)) return false;
  stiffness_ = k;
  damping_ = d;
  return true;
}

}  // namespace mrqp::problem
