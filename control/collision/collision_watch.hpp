// An independent measurement of the collision constraints' distances (docs/collision.md,
// "Measuring"): every pair of every CollisionConstraint of a controller's problem, evaluated
// exactly (no bounding-ball filter, no row selection) on a second problem of the same scene whose
// entities are moved to states given from outside (a plant's). Keeps the smallest distance seen and
// the smallest security distance δs of the pairs, for summary.json's `min_distance_m` and
// `delta_s_m`. Allocation-free after construction; meant to run between cycles.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <vector>

#include "collision/collision_constraint.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::collision {

class CollisionWatch {
 public:
  /// `model`: the controller's problem; `shadow`: a problem of the same scene (same entities).
  CollisionWatch(const problem::MultiRobotProblem& model, problem::MultiRobotProblem& shadow)
      : shadow_(shadow) {
    for (int id = 0; id < model.constraintCapacity(); ++id) {
      if (!model.constraintActive(id)) continue;
      const auto* c = dynamic_cast<const problem::CollisionConstraint*>(&model.constraint(id));
      if (c == nullptr) continue;
      constraints_.push_back(c);
      for (int k = 0; k < c->pairCount(); ++k) security_ = std::min(security_, c->pair(k).security);
    }
    for (int i = 0; i < shadow.entityCount(); ++i) {
      q_.emplace_back(shadow.entity(i).nq());
      v_.emplace_back(shadow.entity(i).nv());
    }
  }

  bool enabled() const noexcept { return !constraints_.empty(); }
  double minDistance() const noexcept { return min_; }
  double securityDistance() const noexcept { return security_; }

  /// `state(i, q, v)` fills entity i's measured state; then every pair is measured.
  template <class StateFn>
  void measure(StateFn&& state) {
    if (!enabled()) return;
    for (int i = 0; i < shadow_.entityCount(); ++i) {
      const auto ui = static_cast<std::size_t>(i);
      state(i, q_[ui], v_[ui]);
      shadow_.entity(i).q() = q_[ui];
      shadow_.entity(i).v() = v_[ui];
      shadow_.entity(i).update();
    }
    for (const problem::CollisionConstraint* c : constraints_)
      min_ = std::min(min_, c->measureMinDistance(shadow_));
  }

 private:
  problem::MultiRobotProblem& shadow_;
  std::vector<const problem::CollisionConstraint*> constraints_;
  std::vector<Eigen::VectorXd> q_, v_;
  double min_ = std::numeric_limits<double>::infinity();
  double security_ = std::numeric_limits<double>::infinity();
};

}  // namespace mrqp::collision
