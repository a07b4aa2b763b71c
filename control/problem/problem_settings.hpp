// Settings and fixed capacity of a MultiRobotProblem (docs/problem.md).
#pragma once

#include <Eigen/Core>

#include "qp/qp_solver.hpp"

namespace mrqp::problem {

struct ProblemSettings {
  double dt = 0.001;  ///< control period Δt of eq. 22–24 and of the dampers, s
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  int max_tasks = 32;                ///< tasks that may exist at once
  int max_contacts = 16;             ///< contacts that may exist at once
  int max_contact_generators = 256;  ///< λ variables of all contacts together
  /// Constraint capacity (problem/constraint.hpp). Slots: max_constraints, or, when < 0,
  /// max_com_dampers + max_joint_inequalities. Inequality rows of all constraints together:
  /// max_constraint_rows, or, when < 0, 16 per CoM damper + 1 per joint inequality. Equality rows:
  /// max_constraint_equalities.
  int max_com_dampers = 4;
  int max_joint_inequalities = 8;
  int max_constraints = -1;
  int max_constraint_rows = -1;
  int max_constraint_equalities = 0;
  double contact_stiffness = 100.0;  ///< Baumgarte gains holding established contacts together
  double contact_damping = 20.0;
  /// Look-ahead T of the joint position limits (eq. 23 written with T instead of Δt, T ≥ Δt):
  /// q + q̇T + q̈T² stays within the limits, so a joint brakes before its limit instead of
  /// reaching it at full speed and then needing an infinite deceleration.
  double joint_limit_horizon = 0.05;
  double regularisation = 1e-6;  ///< weight of ‖q̈‖² + ‖λ‖², keeps the Hessian definite
  qp::QpSettings qp;
};

}  // namespace mrqp::problem
