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

/// Largest capacity a problem accepts (docs/robustness.md, "Readers and limits"), whatever sets it
/// (a scene file, a program): the dense QP they size stays within a few hundred megabytes, and no
/// sum or product of them overflows an int.
constexpr int kMaxTasksCapacity = 256;
constexpr int kMaxContactsCapacity = 64;
constexpr int kMaxContactGeneratorsCapacity = 1024;
constexpr int kMaxConstraintsCapacity = 1024;
constexpr int kMaxConstraintRowsCapacity = 4096;
constexpr int kMaxConstraintEqualitiesCapacity = 1024;

/// nullptr when every capacity of `s` is within its limit (negative values where the field says
/// "when < 0" count as their derived value), else a message naming the first one that is not.
inline const char* capacityError(const ProblemSettings& s) noexcept {
  if (s.max_tasks < 0 || s.max_tasks > kMaxTasksCapacity) return "max_tasks must be in [0, 256]";
  if (s.max_contacts < 0 || s.max_contacts > kMaxContactsCapacity) return "max_contacts must be in [0, 64]";
  if (s.max_contact_generators < 0 || s.max_contact_generators > kMaxContactGeneratorsCapacity) {
    return "max_contact_generators must be in [0, 1024]";
  }
  if (s.max_com_dampers < 0 || s.max_com_dampers > kMaxConstraintsCapacity) {
    return "max_com_dampers must be in [0, 1024]";
  }
  if (s.max_joint_inequalities < 0 || s.max_joint_inequalities > kMaxConstraintsCapacity) {
    return "max_joint_inequalities must be in [0, 1024]";
  }
  const long long slots = s.max_constraints >= 0
                              ? s.max_constraints
                              : static_cast<long long>(s.max_com_dampers) + s.max_joint_inequalities;
  if (slots > kMaxConstraintsCapacity) return "constraint slots (max_constraints) must be at most 1024";
  const long long rows = s.max_constraint_rows >= 0 ? s.max_constraint_rows
                                                    : 16LL * s.max_com_dampers + s.max_joint_inequalities;
  if (rows > kMaxConstraintRowsCapacity) return "constraint rows (max_constraint_rows) must be at most 4096";
  if (s.max_constraint_equalities > kMaxConstraintEqualitiesCapacity) {
    return "max_constraint_equalities must be at most 1024";
  }
  return nullptr;
}

}  // namespace mrqp::problem
