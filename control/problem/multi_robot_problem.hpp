// The multi-robot QP of eq. 25 (docs/problem.md): every entity (robot, free object, mechanism,
// human) in one problem over x = [q̈₁ … q̈ₙ ; λ], with
//
//   equalities    the unactuated rows of the stacked EoM (13), the no-slip constraints of every
//                 active contact (15–16) at the acceleration level;
//   inequalities  torque limits (20) on the actuated rows of the EoM — τ is eliminated through
//                 the EoM, τ = M q̈ + N − Σ Jᵀf, and recovered after the solve —, the CoM
//                 support-region damper (paper 2, eq. 7), velocity dampers on joint inequalities;
//   bounds        joint velocity and position limits (22–23) on q̈, λ ≥ 0 (17);
//   cost          Σ w_k ‖Sel_k (J_k q̈ + J̇_k q̇ − g̈ᵈ_k)‖² (25–26) + regularisation.
//
// Contacts, tasks and dampers live in slots whose number is fixed at construction: adding,
// removing and re-weighting them between cycles never allocates. update(), solve() and every
// accessor are noexcept and allocation-free.
#pragma once

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "problem/contact.hpp"
#include "problem/entity.hpp"
#include "problem/problem_settings.hpp"
#include "problem/support_polygon.hpp"
#include "problem/task.hpp"
#include "qp/qp_problem.hpp"
#include "qp/qp_solver.hpp"

namespace mrqp::problem {

/// A linear inequality Σ cᵢ qᵢ ≤ upper over joints of one or several entities, kept by a velocity
/// damper: with s = upper − Σ cᵢ qᵢ, ṡ + s̈ Δt ≥ −ξ (s − s_s)/(s_i − s_s) whenever s < s_i.
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

/// The CoM damper of one entity (paper 2, eq. 7) over the convex hull of its active contacts
/// with the environment.
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
  static constexpr int kDamperRows = 16;  ///< rows reserved per CoM damper (polygon edges)

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
  /// Adds a task; returns its id or −1. A posture task takes the entity's current joint positions
  /// as its target (change it with setPostureTarget).
  int addTask(const TaskDesc& t) noexcept;
  bool removeTask(int id) noexcept;
  bool taskActive(int id) const noexcept;
  bool setTaskWeight(int id, double weight) noexcept;
  /// Stiffness K and damping D (D < 0: critical, 2√K).
  bool setTaskGains(int id, double stiffness, double damping = -1.0) noexcept;
  bool setTaskTarget(int id, const Eigen::Vector3d& target) noexcept;
  bool setTaskTargetRotation(int id, const Eigen::Matrix3d& R) noexcept;
  /// Joint targets of a posture task (size nv − jointOffset() of its entity).
  bool setPostureTarget(int id, const Eigen::Ref<const Eigen::VectorXd>& q_joints) noexcept;
  const TaskDesc& task(int id) const noexcept { return tasks_[static_cast<std::size_t>(id)].d; }
  int taskCapacity() const noexcept { return static_cast<int>(tasks_.size()); }
  /// Current value of a task (Com, frame and joint tasks: position / rotation vector / value)
  /// and its error g − gʳᵉᶠ, after update(); rows as the task's (angular first for a pose).
  Vector6d taskError(int id) const noexcept;

  // ---- dampers ----
  int addComDamper(const ComDamperDesc& d) noexcept;
  int addJointInequality(const JointInequalityDesc& d) noexcept;
  bool removeJointInequality(int id) noexcept;
  const SupportPolygon& supportPolygon(int damper) const noexcept {
    return dampers_[static_cast<std::size_t>(damper)].polygon;
  }

  // ---- the cycle ----
  /// Updates every entity's model at its current state and assembles the QP.
  UpdateStatus update() noexcept;
  /// Solves the assembled QP and, when Optimal, extracts q̈, τ, λ and the contact wrenches.
  /// On any other status the previous results are kept and must not be applied.
  qp::QpStatus solve() noexcept;
  /// Advances every entity by its q̈ over dt (semi-implicit Euler): the model as its own plant.
  void integrate(double dt) noexcept;

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
  int lambdaOffset(int contact) const noexcept { return contacts_[static_cast<std::size_t>(contact)].var_offset; }

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
    Eigen::Vector3d c_local = Eigen::Vector3d::Zero();   // centroid, surface frame
    Eigen::Vector3d c_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d target_p = Eigen::Vector3d::Zero();  // environment: centroid; other: in its frame
    Eigen::Matrix3d target_R = Eigen::Matrix3d::Identity();  // environment: R_sf; other: R_ofᵀR_sf
    Eigen::Matrix<double, 6, kMaxContactPoints * kMaxConeGenerators> W;  // wrench basis about c
    Eigen::Matrix<double, kMaxContactPoints * kMaxConeGenerators, 1> lambda;
    Vector6d wrench = Vector6d::Zero();
  };
  struct TaskSlot {
    TaskDesc d;
    bool used = false;
    Eigen::VectorXd posture;  // joint targets of a posture task (max nv)
    Vector6d error = Vector6d::Zero();
  };
  struct DamperSlot {
    ComDamperDesc d;
    bool used = false;
    SupportPolygon polygon;
  };
  struct JointIneqSlot {
    JointInequalityDesc d;
    bool used = false;
  };

  void establish(ContactSlot& c) noexcept;
  void layout() noexcept;
  void assembleContacts() noexcept;
  void assembleDynamics() noexcept;
  void assembleBounds() noexcept;
  void assembleDampers() noexcept;
  void assembleTasks() noexcept;
  void addTaskCost(TaskSlot& t) noexcept;
  // Adds w·Σ_r sel_r (T_r x − t_r)² with T given over columns [c0, c0 + nc).
  void accumulate(int rows, int c0, int nc, const std::array<std::uint8_t, 6>& sel, double w) noexcept;
  double kd(const TaskDesc& t) const noexcept;

  ProblemSettings settings_;
  std::vector<std::unique_ptr<Entity>> entities_;
  std::vector<int> v_offset_;
  int nv_total_ = 0, max_nv_ = 0;
  std::vector<ContactSlot> contacts_;
  std::vector<TaskSlot> tasks_;
  std::vector<DamperSlot> dampers_;
  std::vector<JointIneqSlot> joint_ineqs_;
  int nlambda_ = 0, ncontact_rows_ = 0, nunactuated_ = 0, ntorque_rows_ = 0;

  qp::QpProblem qp_;
  qp::QpSolver solver_;
  Eigen::MatrixXd E_;        // stacked EoM rows: τ = E x + N on actuated rows (Σnv × n)
  Eigen::VectorXd Nall_;     // stacked N
  Eigen::MatrixXd Ja_, Jb_;  // 6 × max nv work
  Eigen::MatrixXd T_;        // task rows, 6 × n
  Eigen::Matrix<double, 6, 1> t_;
  Eigen::VectorXd x_, tau_;
  const char* error_ = "";
};

}  // namespace mrqp::problem
