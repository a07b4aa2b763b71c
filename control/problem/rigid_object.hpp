// A free rigid body (a box to carry, a tool) as a one-body floating-base Entity, written by hand.
// Same conventions as a generated floating-base model of the same body (docs/model_gen.md), so the
// two are interchangeable:
//
//   q = [p (3); quaternion w, x, y, z (4)]    the pose of the object frame in the world,
//   v = [ω (3); v (3)]                        the body twist, both in the object frame,
//
// and integrate() moves the pose along the SE(3) exponential of v·dt. The dynamics are the
// Newton–Euler equations of the body at the object-frame origin, in object axes:
//
//   M = [ Ī_O     m [c]× ]      N = v ×* (M v) − (m c × g_b; m g_b),   g_b = Rᵀ g.
//       [ −m [c]×  m 1   ]
//
// There is a single frame, the object frame (named after the entity unless told otherwise), no
// joint and nothing actuated. As for every floating-base entity, the placement base_pose is not
// used: the pose of the object is q.
#pragma once

#include <Eigen/Core>

#include <string>

#include "problem/entity.hpp"

namespace mrqp::problem {

class RigidObject final : public Entity {
 public:
  /// (m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz) about the object origin, in object axes:
  /// the layout of a body's parameters in the generated models.
  using InertialParameters = Eigen::Matrix<double, 10, 1>;

  /// `com` is the centre of mass in the object frame, `inertia_about_com` the rotational inertia
  /// about it in object axes. Throws std::invalid_argument for a mass that is not finite and
  /// positive, a non-finite centre of mass or inertia, or an inertia that is not symmetric positive
  /// definite.
  RigidObject(std::string name, double mass, const Eigen::Vector3d& com,
              const Eigen::Matrix3d& inertia_about_com, std::string frame_name = "");

  /// The inertial parameters about the object origin (see InertialParameters).
  InertialParameters inertialParameters() const noexcept;
  /// Centre of mass in the object frame.
  const Eigen::Vector3d& localCom() const noexcept { return c_; }
  /// Rotational inertia about the centre of mass, object axes.
  const Eigen::Matrix3d& inertiaAboutCom() const noexcept { return Ic_; }
  /// The 6 × 6 spatial inertia at the object origin in object axes (the constant mass matrix).
  const Eigen::Matrix<double, 6, 6>& spatialInertia() const noexcept { return I6_; }

  /// Replaces the inertial parameters (mass, CoM in the object frame, rotational inertia about the
  /// CoM in object axes) on the cycle: noexcept, allocation-free. The derived quantities (inertia
  /// about the origin, spatial inertia) are recomputed and so are M, N and the CoM of the current
  /// state (as update() does). Returns false and changes nothing for the inputs the constructor
  /// refuses (mass not finite and positive, non-finite CoM, inertia not symmetric positive definite).
  bool setInertia(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& inertia_about_com) noexcept;
  /// The same from parameters about the object origin (InertialParameters' layout, e.g. an
  /// estimate): c = h / m, I_c = I_O − m [c]×[c]×ᵀ.
  bool setInertialParameters(const InertialParameters& phi) noexcept;

  int frameCount() const noexcept override { return 1; }
  const char* frameName(int frame) const noexcept override;
  int frameIndex(const std::string& name) const noexcept override;
  const char* jointName(int joint) const noexcept override;
  void neutral(Eigen::Ref<Eigen::VectorXd> q) const noexcept override;

  Pose framePose(int frame) const noexcept override;
  void frameJacobian(int frame, const Eigen::Vector3d& point,
                     Eigen::Ref<Eigen::MatrixXd> J) const noexcept override;
  Vector6d frameBiasAcceleration(int frame, const Eigen::Vector3d& point) const noexcept override;

 private:
  void computeDynamics() noexcept override;
  void integrateConfiguration(double dt) noexcept override;
  /// The inertia's failure as text, nullptr when valid (for the constructor's message).
  static const char* inertiaProblem(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& Ic,
                                    double* detail) noexcept;
  void assignInertia(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& Ic) noexcept;

  std::string frame_name_;
  Eigen::Vector3d c_;               ///< centre of mass, object frame
  Eigen::Matrix3d Ic_;              ///< rotational inertia about the centre of mass
  Eigen::Matrix3d Io_;              ///< rotational inertia about the object origin
  Eigen::Matrix<double, 6, 6> I6_;  ///< spatial inertia at the origin
  // State of the last update(): pose and body twist.
  Eigen::Matrix3d R_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_ = Eigen::Vector3d::Zero();
};

}  // namespace mrqp::problem
