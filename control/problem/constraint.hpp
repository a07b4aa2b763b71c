// The interface of a constraint kind of the multi-robot QP beyond its core (the EoM, contacts,
// torque limits and joint bounds stay in MultiRobotProblem): velocity dampers (eq. 21, 24;
// paper 2, eq. 7), and whatever kind comes next (collision avoidance, cascaded equalities).
//
// A constraint reserves a fixed number of inequality rows l ≤ C x ≤ u and of equality rows
// A x = b in every QP; update() fills them. Rows it leaves alone stay free (C = 0, l = −∞,
// u = +∞) or, for equalities, 0 = 0. Built at set-up, handed to MultiRobotProblem::addConstraint;
// update() is noexcept and allocation-free. One class per kind, in problem/constraints/.
#pragma once

#include <Eigen/Core>

namespace mrqp::problem {

class MultiRobotProblem;

/// A constraint's block of the QP, every column of x: its inequality rows (C, l, u) and its
/// equality rows (A, b). All come zeroed, l = −∞ and u = +∞.
struct ConstraintRows {
  Eigen::Ref<Eigen::MatrixXd> C;
  Eigen::Ref<Eigen::VectorXd> l;
  Eigen::Ref<Eigen::VectorXd> u;
  Eigen::Ref<Eigen::MatrixXd> A;
  Eigen::Ref<Eigen::VectorXd> b;
};

class Constraint {
 public:
  virtual ~Constraint() = default;
  Constraint(const Constraint&) = delete;
  Constraint& operator=(const Constraint&) = delete;

  /// The kind's name ("com_damper", "joint_inequality", ...).
  virtual const char* kind() const noexcept = 0;
  /// Inequality rows reserved in every QP while the constraint is active.
  virtual int inequalityRows() const noexcept = 0;
  /// Equality rows reserved in every QP while the constraint is active.
  virtual int equalityRows() const noexcept { return 0; }
  /// Checks the constraint against the problem: nullptr when it fits, else why not.
  virtual const char* check(const MultiRobotProblem& p) const noexcept = 0;
  /// Reads the entities' and contacts' state (after their update) and writes its rows.
  virtual void update(const MultiRobotProblem& p, ConstraintRows& rows) noexcept = 0;

 protected:
  Constraint() = default;
};

}  // namespace mrqp::problem
