// One "robot" of the multi-robot problem (eq. 1): a robot, a free rigid object or a passive
// mechanism, seen through a model-independent interface with dynamic-size views.
//
//   M(q) q̈ + N(q, q̇) + τ_spring(q, q̇) = Σ Jᵀ f + S τ
//
// Conventions (docs/problem.md): q and v as in the generated models (a floating base has
// q = [p; w x y z; joints] and v = body twist (ω; v) in the root-link frame, then joint rates).
// Every world quantity includes the entity's placement (base_pose), so a fixed-base door can stand
// anywhere in the world. Jacobians and bias accelerations returned here are world-aligned, at a
// point given in the frame's coordinates, rows (ω; v).
//
// Real-time: update() and every query are noexcept and allocation-free; storage is sized once by
// the constructor of the concrete entity.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace mrqp::problem {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A rigid transform: x_world = R x_local + p.
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

/// Joint spring of a passive mechanism (paper 1, eq. 48): the joint feels −(K q + C q̇ + O).
struct JointSpring {
  double stiffness = 0.0;  ///< K, N·m/rad
  double damping = 0.0;    ///< C, N·m·s/rad
  double offset = 0.0;     ///< O, N·m
};

class Entity {
 public:
  virtual ~Entity() = default;
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;

  const std::string& name() const noexcept { return name_; }
  int nq() const noexcept { return nq_; }
  int nv() const noexcept { return nv_; }
  bool floatingBase() const noexcept { return floating_; }
  /// First velocity index of the joints (6 with a floating base, else 0).
  int jointOffset() const noexcept { return floating_ ? 6 : 0; }
  double mass() const noexcept { return mass_; }

  // ---- model description (set at construction) ----
  virtual int frameCount() const noexcept = 0;
  virtual const char* frameName(int frame) const noexcept = 0;
  /// Frame index, −1 when unknown.
  virtual int frameIndex(const std::string& name) const noexcept = 0;
  /// Names of the joints in velocity order after the base (size nv − jointOffset()).
  virtual const char* jointName(int joint) const noexcept = 0;
  /// Velocity index of the named joint, −1 when unknown.
  int jointIndex(const std::string& name) const noexcept;

  /// Position limits per joint velocity coordinate (size nv; ±inf for the base and unlimited joints).
  const Eigen::VectorXd& qLower() const noexcept { return q_lower_; }
  const Eigen::VectorXd& qUpper() const noexcept { return q_upper_; }
  const Eigen::VectorXd& vLimit() const noexcept { return v_limit_; }
  const Eigen::VectorXd& effortLimit() const noexcept { return effort_limit_; }
  /// Joint coordinate of velocity index k in q (k ≥ jointOffset()).
  int qIndexOfV(int k) const noexcept { return floating_ ? k + 1 : k; }

  // ---- actuation (S of eq. 1 as a selection) and springs ----
  /// 1 where the velocity coordinate is driven by a motor. The base never is.
  const std::vector<std::uint8_t>& actuated() const noexcept { return actuated_; }
  bool fullyActuated() const noexcept;
  /// Marks velocity coordinate k (k ≥ jointOffset()) actuated or passive.
  bool setActuated(int k, bool on) noexcept;
  void setAllJointsActuated(bool on) noexcept;
  bool setSpring(int k, const JointSpring& s) noexcept;
  const std::vector<JointSpring>& springs() const noexcept { return springs_; }

  // ---- placement of a fixed base (ignored with a floating base, whose pose is in q) ----
  const Pose& basePose() const noexcept { return base_; }
  /// Gravity in world axes (default (0, 0, −9.81)).
  void setGravity(const Eigen::Vector3d& g) noexcept { gravity_ = g; }
  void setBasePose(const Pose& p) noexcept { base_ = p; }

  // ---- state ----
  Eigen::Ref<Eigen::VectorXd> q() noexcept { return q_; }
  Eigen::Ref<Eigen::VectorXd> v() noexcept { return v_; }
  Eigen::Ref<const Eigen::VectorXd> q() const noexcept { return q_; }
  Eigen::Ref<const Eigen::VectorXd> v() const noexcept { return v_; }
  /// The neutral configuration (identity base at the origin, joints at 0 or their mid-range).
  virtual void neutral(Eigen::Ref<Eigen::VectorXd> q) const noexcept = 0;
  /// v ← v + a·dt, then q ← q ⊕ v·dt (semi-implicit Euler on the configuration manifold).
  void integrate(const Eigen::Ref<const Eigen::VectorXd>& a, double dt) noexcept;

  /// Evaluates kinematics and dynamics at the current (q, v): frame poses, M, N (with springs),
  /// CoM, its Jacobian and bias. Call once per cycle before the queries below.
  void update() noexcept;
  /// Evaluates the kinematics alone at the current (q, v): frame poses, frame Jacobians and their
  /// J̇v, not M, N or the CoM. For a world that is only looked at (a plant's sensors, a contact
  /// fit); the dynamic quantities keep the values of the last update().
  void updateKinematics() noexcept { computeKinematics(); }

  const Eigen::MatrixXd& massMatrix() const noexcept { return M_; }
  /// N(q, v) + spring torques: everything on the left of eq. 1 that does not multiply q̈.
  const Eigen::VectorXd& bias() const noexcept { return N_; }
  const Eigen::Vector3d& com() const noexcept { return com_; }
  /// World CoM Jacobian (3 × nv) and its bias J̇c v, after update().
  const Eigen::MatrixXd& comJacobian() const noexcept { return Jc_; }
  const Eigen::Vector3d& comBias() const noexcept { return com_bias_; }

  /// World pose of a frame (after update()).
  virtual Pose framePose(int frame) const noexcept = 0;
  /// World-aligned 6 × nv Jacobian of the point `point` (frame coordinates) of a frame.
  virtual void frameJacobian(int frame, const Eigen::Vector3d& point,
                             Eigen::Ref<Eigen::MatrixXd> J) const noexcept = 0;
  /// J̇ v for that Jacobian: (angular acceleration; classical point acceleration) at q̈ = 0.
  virtual Vector6d frameBiasAcceleration(int frame, const Eigen::Vector3d& point) const noexcept = 0;

  /// The generalised force of the joint springs at the current state (size nv).
  void springTorque(Eigen::Ref<Eigen::VectorXd> out) const noexcept;

 protected:
  Entity(std::string name, int nq, int nv, bool floating_base);

  /// Model hooks for update(): at the state (q_, v_) with gravity expressed in the model's base
  /// frame, fill M_, N_ (without springs), com_, Jc_ and com_bias_ in world axes.
  virtual void computeDynamics() noexcept = 0;
  /// The kinematic part of computeDynamics (frame poses and velocities); by default all of it.
  virtual void computeKinematics() noexcept { computeDynamics(); }
  virtual void integrateConfiguration(double dt) noexcept = 0;

  std::string name_;
  int nq_, nv_;
  bool floating_;
  double mass_ = 0.0;
  Pose base_;
  Eigen::VectorXd q_, v_, q_lower_, q_upper_, v_limit_, effort_limit_;
  std::vector<std::uint8_t> actuated_;
  std::vector<JointSpring> springs_;
  Eigen::MatrixXd M_, Jc_;
  Eigen::VectorXd N_, spring_work_;
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero(), com_bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gravity_{0.0, 0.0, -9.81};
};

}  // namespace mrqp::problem
