// The interface of a weighted task of the multi-robot QP (eq. 25–26; docs/problem.md, "Tasks").
//
// A task contributes w·‖Sel (T x − t)‖² to the cost. Kinematic tasks write T = J (their Jacobian
// over x) and t = g̈ᵈ − J̇q̇ with the PD-shaped desired acceleration of eq. 26,
//
//   g̈ᵈ = g̈ʳᵉᶠ − K (g − gʳᵉᶠ) − D (ġ − ġʳᵉᶠ),   D = 2√K (critical damping) unless given,
//
// where the position reference gʳᵉᶠ (the target), the velocity reference ġʳᵉᶠ and the acceleration
// reference g̈ʳᵉᶠ vary in time (setReference): a trajectory or the admittance drives them.
//
// A task is an object built at set-up (it may allocate there: its references are sized by its
// dimension) and handed to MultiRobotProblem::addTask, which holds it in a slot. Every call made on
// the control cycle (update, the setters) is noexcept and allocation-free. One class per kind, in
// problem/tasks/.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>

#include "problem/entity.hpp"

namespace mrqp::problem {

class MultiRobotProblem;

/// Where a task writes its rows. The problem owns the storage (capacity fixed at construction):
/// either T (6 × n rows, rows ≤ 6, only columns [col0, col0 + cols) are read) and t, or, when
/// `identity` is set, T is the identity over columns [col0, col0 + rows) and only t is written
/// (posture, joint and force-minimisation tasks: rows up to the largest entity's nv or the λ count).
struct TaskRows {
  Eigen::MatrixXd& T;
  Eigen::VectorXd& t;
  int rows = 0;
  int col0 = 0;
  int cols = 0;
  bool identity = false;
};

class Task {
 public:
  using Selection = std::array<std::uint8_t, 6>;

  virtual ~Task() = default;
  Task(const Task&) = delete;
  Task& operator=(const Task&) = delete;

  /// The kind's name as in scene files ("posture", "frame_pose", ...).
  virtual const char* kind() const noexcept = 0;
  /// Checks the task against the problem's entities and contacts: nullptr when it fits, else why
  /// not. Called by addTask.
  virtual const char* check(const MultiRobotProblem& p) const noexcept = 0;
  /// Called by addTask once the task has a slot (e.g. a posture task without a target takes the
  /// entity's current joint positions).
  virtual void attach(const MultiRobotProblem& /*p*/) noexcept {}
  /// Reads the entities' state (after their update), writes the task's rows and its error.
  /// Returns false when the task has nothing to add this cycle (e.g. its contact is gone).
  virtual bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept = 0;

  /// Position targets; each returns false when the kind has no such target or the value is bad.
  virtual bool setTarget(const Eigen::Vector3d& /*target*/) noexcept { return false; }
  virtual bool setTargetRotation(const Eigen::Matrix3d& /*R*/) noexcept { return false; }
  /// A target of the task's full dimension (posture: the entity's joints).
  virtual bool setTargetVector(const Eigen::Ref<const Eigen::VectorXd>& /*target*/) noexcept { return false; }

  /// Rows of ġʳᵉᶠ and g̈ʳᵉᶠ (the task's dimension before selection).
  int referenceRows() const noexcept { return static_cast<int>(velocity_ref_.size()); }
  /// Velocity and acceleration references (zero until set). False when a size is wrong or a value
  /// is not finite.
  bool setReference(const Eigen::Ref<const Eigen::VectorXd>& velocity,
                    const Eigen::Ref<const Eigen::VectorXd>& acceleration) noexcept;
  const Eigen::VectorXd& velocityReference() const noexcept { return velocity_ref_; }
  const Eigen::VectorXd& accelerationReference() const noexcept { return acceleration_ref_; }

  double weight() const noexcept { return weight_; }
  double stiffness() const noexcept { return stiffness_; }
  /// D as given (< 0: critical).
  double damping() const noexcept { return damping_; }
  /// D as used: the given one, or 2√K.
  double dampingUsed() const noexcept;
  const Selection& selection() const noexcept { return dims_; }
  bool setWeight(double w) noexcept;
  /// Stiffness K and damping D (D < 0: critical, 2√K).
  bool setGains(double stiffness, double damping = -1.0) noexcept;
  /// Selector over the task's first six rows (identity-row tasks have none and ignore it).
  void setSelection(const Selection& dims) noexcept { dims_ = dims; }

  /// Value minus target after the last update (rows as the task's; angular first for a pose).
  const Vector6d& error() const noexcept { return error_; }

 protected:
  /// reference_rows: the task's dimension (size of ġʳᵉᶠ and g̈ʳᵉᶠ).
  explicit Task(int reference_rows);

  Vector6d error_ = Vector6d::Zero();

 private:
  double weight_ = 1.0;
  double stiffness_ = 10.0;
  double damping_ = -1.0;
  Selection dims_{{1, 1, 1, 1, 1, 1}};
  Eigen::VectorXd velocity_ref_, acceleration_ref_;
};

}  // namespace mrqp::problem
