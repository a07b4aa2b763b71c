// The multi-robot QP of eq. 25 (docs/problem.md): every entity (robot, free object, mechanism,
// human) in one problem over x = [q̈₁ … q̈ₙ ; λ], with
//
//   equalities    the unactuated rows of the stacked EoM (13), the no-slip constraints of every
//                 active contact (15–16) at the acceleration level;
//   inequalities  torque limits (20) on the actuated rows of the EoM — τ is eliminated through
//                 the EoM, τ = M q̈ + N − Σ Jᵀf, and recovered after the solve —, and the rows
//                 of every constraint object (problem/constraint.hpp: the CoM support-region
//                 damper of paper 2, eq. 7, velocity dampers on joint inequalities, ...);
//   bounds        joint velocity and position limits (22–23) on q̈, λ ≥ 0 (17);
//   cost          Σ w_k ‖Sel_k (T_k x − t_k)‖² over the task objects (problem/task.hpp; eq.
//                 25–26) + regularisation.
//
// Contacts, tasks and constraints live in slots whose number is fixed at construction. Task and
// constraint objects are built at set-up and handed over (addTask, addConstraint); removing,
// restoring, re-weighting and re-targeting them between cycles never allocates. update(), solve()
// and every accessor are noexcept and allocation-free.
#pragma once

#include <Eigen/Core>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "problem/constraint.hpp"
#include "problem/constraints/joint_inequality.hpp"
#include "problem/contact.hpp"
#include "problem/entity.hpp"
#include "problem/problem_settings.hpp"
#include "problem/support_polygon.hpp"
#include "problem/task.hpp"
#include "qp/qp_problem.hpp"
#include "qp/qp_solver.hpp"

namespace mrqp::problem {

/// Plain descriptions of the two velocity-damper constraints, for addJointInequality and
/// addComDamper (set-up helpers that build the constraint object; see problem/constraints/).
struct JointInequalityDesc {
  static constexpr int kMaxTerms = 4;
  int terms = 0;
  std::array<int, kMaxTerms> entity{};
  std::array<int, kMaxTerms> joint{};  ///< velocity index within the entity
  std::array<double, kMaxTerms> coeff{};
  double upper = 0.0;
  double interaction = 0.05;  ///< s_i
  double security = 0.0;      ///< s_s
  double damping = 0.5;       ///< ξ
};

struct ComDamperDesc {
  int entity = -1;
  double interaction = 0.05;  ///< d_i, m
  double security = 0.01;     ///< d_s, m
  double damping = 0.5;       ///< ξ, m/s
};

enum class UpdateStatus : std::uint8_t {
  Ok,
  NonFiniteState,  ///< an entity's q or v holds NaN/inf: nothing was assembled
};

class MultiRobotProblem {
 public:
  static constexpr int kMaxEntities = 32;

  /// Takes the entities (at most kMaxEntities) and allocates every buffer for the capacity.
  MultiRobotProblem(std::vector<std::unique_ptr<Entity>> entities, const ProblemSettings& settings);

  const ProblemSettings& settings() const noexcept { return settings_; }
  int entityCount() const noexcept { return static_cast<int>(entities_.size()); }
  Entity& entity(int i) noexcept { return *entities_[static_cast<std::size_t>(i)]; }
  const Entity& entity(int i) const noexcept { return *entities_[static_cast<std::size_t>(i)]; }
  int entityIndex(const std::string& name) const noexcept;
  /// Column of entity i's q̈ in x.
  int velocityOffset(int i) const noexcept { return v_offset_[static_cast<std::size_t>(i)]; }
  int totalVelocities() const noexcept { return nv_total_; }

  // ---- contacts ----
  /// Adds a contact; it is established (its relative pose frozen) at the next update().
  /// Returns its id, or −1 (see lastError()) when invalid or over capacity.
  int addContact(const ContactDesc& c) noexcept;
  bool removeContact(int id) noexcept;
  bool contactActive(int id) const noexcept;
  const ContactDesc& contact(int id) const noexcept { return contacts_[static_cast<std::size_t>(id)].d; }
  int contactCapacity() const noexcept { return static_cast<int>(contacts_.size()); }

  // ---- tasks ----
  /// Adds a task built at set-up: checks it, puts it in a free slot and attach()es it (a posture
  /// task without a target takes the entity's current joint positions). Returns its id, or −1
  /// (see lastError()) when invalid or no slot is free. Allocation-free, except that when only
  /// slots of removed tasks are left the oldest such task object is destroyed.
  int addTask(std::unique_ptr<Task> task) noexcept;
  /// Deactivates a task; the object stays in its slot (restoreTask brings it back).
  bool removeTask(int id) noexcept;
  /// Re-activates a removed task under the same id. Allocation-free.
  bool restoreTask(int id) noexcept;
  /// Hands a task object (active or removed) back to the caller; its slot becomes free.
  std::unique_ptr<Task> releaseTask(int id) noexcept;
  bool taskActive(int id) const noexcept;
  bool setTaskWeight(int id, double weight) noexcept;
  /// Stiffness K and damping D (D < 0: critical, 2√K).
  bool setTaskGains(int id, double stiffness, double damping = -1.0) noexcept;
  bool setTaskTarget(int id, const Eigen::Vector3d& target) noexcept;
  bool setTaskTargetRotation(int id, const Eigen::Matrix3d& R) noexcept;
  /// Joint targets of a posture task (size nv − jointOffset() of its entity).
  bool setPostureTarget(int id, const Eigen::Ref<const Eigen::VectorXd>& q_joints) noexcept;
  /// Velocity and acceleration references ġʳᵉᶠ, g̈ʳᵉᶠ of eq. 26 (size: the task's dimension,
  /// Task::referenceRows(); rows as the task's, angular first for a pose).
  bool setTaskReference(int id, const Eigen::Ref<const Eigen::VectorXd>& velocity,
                        const Eigen::Ref<const Eigen::VectorXd>& acceleration) noexcept;
  /// Position, velocity and acceleration references of a three-row task (CoM, frame position).
  bool setTaskReference(int id, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                        const Eigen::Vector3d& acceleration) noexcept;
  /// The task object of a slot (active or removed; the slot must hold one).
  const Task& task(int id) const noexcept { return *tasks_[static_cast<std::size_t>(id)].task; }
  Task& task(int id) noexcept { return *tasks_[static_cast<std::size_t>(id)].task; }
  int taskCapacity() const noexcept { return static_cast<int>(tasks_.size()); }
  /// Error g − gʳᵉᶠ of an active task after update() (Task::error(); zero for posture and force
  /// minimisation); rows as the task's (angular first for a pose).
  Vector6d taskError(int id) const noexcept;

  // ---- constraints ----
  /// Adds a constraint built at set-up into a free slot; returns its id or −1 (see lastError()).
  /// Its rows are reserved from the next update(). Same slot rules as addTask.
  int addConstraint(std::unique_ptr<Constraint> constraint) noexcept;
  bool removeConstraint(int id) noexcept;
  bool restoreConstraint(int id) noexcept;
  std::unique_ptr<Constraint> releaseConstraint(int id) noexcept;
  bool constraintActive(int id) const noexcept;
  const Constraint& constraint(int id) const noexcept {
    return *constraints_[static_cast<std::size_t>(id)].constraint;
  }
  Constraint& constraint(int id) noexcept { return *constraints_[static_cast<std::size_t>(id)].constraint; }
  int constraintCapacity() const noexcept { return static_cast<int>(constraints_.size()); }

  /// Builds a JointInequality in a free slot's own storage and adds it: allocation-free, may be
  /// called between cycles. Returns the constraint id or −1. (releaseConstraint of it returns
  /// nullptr: the object lives in the slot.)
  int addJointInequality(const JointInequalityDesc& d) noexcept;
  /// Builds a ComDamper and adds it. Set-up only: allocates the object.
  int addComDamper(const ComDamperDesc& d) noexcept;
  bool removeJointInequality(int id) noexcept { return removeConstraint(id); }

  // ---- the cycle ----
  /// Updates every entity's model at its current state and assembles the QP.
  UpdateStatus update() noexcept;
  /// Solves the assembled QP and, when Optimal, extracts q̈, τ, λ and the contact wrenches.
  /// On any other status the previous results are kept and must not be applied.
  qp::QpStatus solve() noexcept;

  // ---- results of the last Optimal solve ----
  Eigen::Ref<const Eigen::VectorXd> acceleration(int entity) const noexcept;
  /// τ of eq. 1 (zero on passive coordinates and on the base).
  Eigen::Ref<const Eigen::VectorXd> torque(int entity) const noexcept;
  Eigen::Ref<const Eigen::VectorXd> lambda(int contact) const noexcept;
  /// Force on the surface entity (world axes) and its moment about contactPoint(): (moment; force).
  /// The other entity receives exactly the opposite wrench at the same point.
  Vector6d contactWrench(int contact) const noexcept;
  Eigen::Vector3d contactForce(int contact) const noexcept { return contactWrench(contact).tail<3>(); }
  /// The point (world) about which the contact wrench is given: the surface points' centroid.
  const Eigen::Vector3d& contactPoint(int contact) const noexcept {
    return contacts_[static_cast<std::size_t>(contact)].c_world;
  }
  /// Column of a contact's first λ in x (−1 when inactive), after update().
  int lambdaOffset(int contact) const noexcept {
    return contacts_[static_cast<std::size_t>(contact)].var_offset;
  }
  /// λ variables of every active contact, after update() (they follow the q̈ in x, in slot order).
  int lambdaCount() const noexcept { return nlambda_; }
  /// The wrench basis W of a contact after update(): its wrench is W λ (moment about
  /// contactPoint(); force), columns 0 … variables() − 1.
  const Eigen::Matrix<double, 6, kMaxContactPoints * kMaxConeGenerators>& contactWrenchBasis(
      int contact) const noexcept {
    return contacts_[static_cast<std::size_t>(contact)].W;
  }
  /// A 6 × (largest nv) scratch matrix for task and constraint objects within their update().
  Eigen::MatrixXd& jacobianWork() const noexcept { return Jw_; }

  const qp::QpProblem& qp() const noexcept { return qp_; }
  const qp::QpSolver& solver() const noexcept { return solver_; }
  qp::QpSolver& solver() noexcept { return solver_; }
  /// The full solution vector x of the last Optimal solve.
  Eigen::Ref<const Eigen::VectorXd> solution() const noexcept { return x_.head(qp_.n()); }
  const char* lastError() const noexcept { return error_; }

 private:
  struct ContactSlot {
    ContactDesc d;
    bool used = false, established = false;
    int var_offset = -1, row_offset = -1;
    // Rows of the no-slip constraint it writes: 0 when an earlier contact joins the same two
    // frames (the constraint belongs to the pair of frames; writing it twice would make the
    // equalities dependent and, with drift correction at two points, inconsistent).
    int rows = 0;
    Eigen::Vector3d c_local = Eigen::Vector3d::Zero();  // centroid, surface frame
    Eigen::Vector3d c_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d target_p = Eigen::Vector3d::Zero();      // environment: centroid; other: in its frame
    Eigen::Matrix3d target_R = Eigen::Matrix3d::Identity();  // environment: R_sf; other: R_ofᵀR_sf
    Eigen::Matrix<double, 6, kMaxContactPoints * kMaxConeGenerators> W;  // wrench basis about c
    Eigen::Matrix<double, kMaxContactPoints * kMaxConeGenerators, 1> lambda;
    Vector6d wrench = Vector6d::Zero();
  };
  struct TaskSlot {
    std::unique_ptr<Task> task;
    bool active = false;
  };
  struct ConstraintSlot {
    std::unique_ptr<Constraint> owned;                // an object handed to addConstraint
    std::optional<JointInequality> joint_inequality;  // built in place by addJointInequality
    Constraint* constraint = nullptr;                 // the one of the two in use, or nullptr
    bool active = false;
    int ineq_row = 0, eq_row = 0;  // first rows in C and A, after layout()
  };
  // Why `c` cannot join the active constraints (check(), rows over capacity), or nullptr.
  const char* admit(const Constraint& c) const noexcept;
  // A slot holding no object, else one holding a removed object (cleared), else −1.
  int takeConstraintSlot() noexcept;

  void establish(ContactSlot& c) noexcept;
  // The no-slip rows of a contact with free directions: one per held direction of its contact
  // frame (frame orientation R_frame), sign · (direction)ᵀ J (J: a world 6 × nv Jacobian).
  static void writeHeldRows(const ContactSlot& c, const Eigen::Matrix3d& R_frame,
                            const Eigen::Ref<const Eigen::MatrixXd>& J, double sign,
                            Eigen::Ref<Eigen::MatrixXd> rows) noexcept;
  void layout() noexcept;
  void assembleContacts() noexcept;
  void assembleDynamics() noexcept;
  void assembleBounds() noexcept;
  void assembleConstraints() noexcept;
  void assembleTasks() noexcept;
  // Adds w·Σ_r sel_r (T_r x − t_r)² for the rows a task wrote.
  void accumulate(const TaskRows& rows, const Task::Selection& sel, double w) noexcept;

  ProblemSettings settings_;
  std::vector<std::unique_ptr<Entity>> entities_;
  std::vector<int> v_offset_;
  int nv_total_ = 0, max_nv_ = 0;
  std::vector<ContactSlot> contacts_;
  std::vector<TaskSlot> tasks_;
  std::vector<ConstraintSlot> constraints_;
  int nlambda_ = 0, ncontact_rows_ = 0, nunactuated_ = 0, ntorque_rows_ = 0;
  int max_constraint_rows_ = 0, max_constraint_equalities_ = 0;

  qp::QpProblem qp_;
  qp::QpSolver solver_;
  Eigen::MatrixXd E_;           // stacked EoM rows: τ = E x + N on actuated rows (Σnv × n)
  Eigen::VectorXd Nall_;        // stacked N
  Eigen::MatrixXd Ja_, Jb_;     // 6 × max nv work
  mutable Eigen::MatrixXd Jw_;  // 6 × max nv scratch of task and constraint objects
  Eigen::MatrixXd T_;           // task rows, 6 × n
  Eigen::VectorXd t_;           // task targets, max(6, max nv, max λ)
  Eigen::VectorXd x_, tau_;
  const char* error_ = "";
};

}  // namespace mrqp::problem
