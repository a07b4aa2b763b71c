// Slow, dynamic-size reference implementation of rigid-body kinematics and dynamics, built
// directly from a URDF file. Test-only: it exists to check the code written by mrqp-gen
// numerically, so it follows the conventions of docs/model_gen.md exactly but shares no code
// with the generator and favours clarity over speed:
//
//  - its own tree: one node per URDF link, a fixed joint is simply a node with zero dof
//    (nothing is merged, except in inertialParameters() which reports merged bodies);
//  - depth-first pre-order from the root link, children visited in lexicographic order of their
//    joint names; frames = every link in that order;
//  - mimic joints: the positions of all moving URDF joints ("full" joint coordinates, DFS order)
//    are G * q_independent + offset, with chains of mimics resolved;
//  - floating base: q = [p (3); quaternion w, x, y, z (4); joints],
//    v = [omega (3); v (3); joint rates], the base twist expressed in the root-link frame;
//  - spatial vectors (angular; linear), Jacobians 6 x nv with rows (omega; v);
//  - gravity (0, 0, -9.81) in the world frame unless changed with setGravity().
//
// Every function is const and recomputes everything it needs from scratch.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mrqp::test {

class ReferenceModel {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;

  /// x_parent = R x + p
  struct Pose {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };

  /// Parses the URDF with urdfdom. Throws std::runtime_error on unreadable or unsupported input.
  static ReferenceModel fromUrdf(const std::string& path, bool floating_base);

  // ---- sizes and names ---------------------------------------------------------------------
  int nq() const;
  int nv() const;
  bool floatingBase() const;
  /// Independent (non-mimic, moving) joints, in v order after the base.
  const std::vector<std::string>& jointNames() const;
  /// Every URDF link, DFS order.
  const std::vector<std::string>& frameNames() const;
  /// -1 when unknown.
  int frameIndex(const std::string& name) const;
  /// Merged bodies (maximal groups of links joined by fixed joints), named after the group's root
  /// link, ordered as those root links in DFS order. The root link's group is body 0 (also with a
  /// fixed base, where it never moves).
  const std::vector<std::string>& bodyNames() const;
  /// Body carrying each frame (index into bodyNames()), in frame order.
  std::vector<int> frameBody() const;

  // ---- mimic map ---------------------------------------------------------------------------
  /// Every moving URDF joint (mimic ones included), DFS order.
  const std::vector<std::string>& fullJointNames() const;
  /// G (fullJointNames().size() x jointNames().size()) and offset:
  /// full joint positions = G * q_joints + offset, full joint rates = G * v_joints.
  const Eigen::MatrixXd& mimicMatrix() const;
  const Eigen::VectorXd& mimicOffset() const;
  Eigen::VectorXd fullJointPositions(const Eigen::VectorXd& q) const;

  // ---- limits (size nq for positions, nv for velocity / effort) -----------------------------
  /// Base entries -inf / +inf; continuous joints -inf / +inf.
  Eigen::VectorXd lowerPositionLimit() const;
  Eigen::VectorXd upperPositionLimit() const;
  /// Base entries +inf; a joint without a <limit> element gets +inf.
  Eigen::VectorXd velocityLimit() const;
  Eigen::VectorXd effortLimit() const;

  // ---- gravity -----------------------------------------------------------------------------
  const Eigen::Vector3d& gravity() const;
  void setGravity(const Eigen::Vector3d& g);

  // ---- configuration space -----------------------------------------------------------------
  /// Base at the origin with the identity orientation, joints at zero.
  Eigen::VectorXd neutral() const;
  /// Base: moves along the SE(3) exponential of the body twist v*dt; joints: q + v*dt.
  Eigen::VectorXd integrate(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double dt) const;

  // ---- kinematics --------------------------------------------------------------------------
  /// World pose of a frame (link). Throws on an unknown name.
  Pose framePose(const Eigen::VectorXd& q, const std::string& frame) const;
  /// 6 x nv, rows (omega; v) of the point given in the frame's coordinates. Local: expressed in
  /// the frame's axes; world_aligned: in the world axes.
  Eigen::MatrixXd frameJacobian(const Eigen::VectorXd& q, const std::string& frame,
                                const Eigen::Vector3d& point_in_frame, bool world_aligned) const;
  /// d/dt (J(q) v) along the motion with zero acceleration (same Jacobian as above).
  Vector6d frameBiasAcceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const std::string& frame,
                                 const Eigen::Vector3d& point_in_frame, bool world_aligned) const;

  // ---- mass properties ---------------------------------------------------------------------
  double totalMass() const;
  /// Mass-weighted sum of link centres of mass (zero when the model has no mass).
  Eigen::Vector3d centerOfMass(const Eigen::VectorXd& q) const;
  /// 3 x nv, world frame.
  Eigen::MatrixXd comJacobian(const Eigen::VectorXd& q) const;
  /// Per merged body (bodyNames() order), in the body frame about the body origin:
  /// (m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz).
  Eigen::VectorXd inertialParameters() const;

  // ---- dynamics ----------------------------------------------------------------------------
  /// Recursive Newton-Euler: tau = M(q) a + C(q, v) v + g(q).
  Eigen::VectorXd rnea(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) const;
  /// rnea(q, v, 0)
  Eigen::VectorXd nonLinearEffects(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  /// Column by column: M e_i = rnea(q, 0, e_i) - rnea(q, 0, 0) with zero gravity.
  Eigen::MatrixXd massMatrix(const Eigen::VectorXd& q) const;

 private:
  enum class JointType { Root, Fixed, Revolute, Prismatic };

  struct Link {
    std::string name;
    std::string joint_name;  // empty for the root
    int parent = -1;
    JointType type = JointType::Root;
    Pose origin;                                      // joint frame in the parent link frame
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, joint frame
    int full_index = -1;                              // index in the full joint coordinates
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();          // link frame
    Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();  // about the CoM, link axes
    int body = -1;                                          // merged body
    Pose in_body;                                           // link frame in body frame
  };

  struct Motion {  // per link, link coordinates
    std::vector<Pose> world;
    std::vector<Vector6d> velocity;
    std::vector<Vector6d> acceleration;
  };

  void checkConfig(const Eigen::VectorXd& q) const;
  void checkTangent(const Eigen::VectorXd& v, const char* what) const;
  int requireFrame(const std::string& name) const;
  int baseDofs() const;
  Pose localPose(int link, const Eigen::VectorXd& q, const Eigen::VectorXd& q_full) const;
  Vector6d motionSubspace(int link) const;
  std::vector<Pose> worldPoses(const Eigen::VectorXd& q) const;
  /// Poses, velocities and accelerations of every link; root acceleration includes -gravity_used.
  Motion propagate(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                   const Eigen::Vector3d& gravity_used) const;
  Eigen::VectorXd rneaWithGravity(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a, const Eigen::Vector3d& g) const;

  bool floating_base_ = false;
  std::vector<Link> links_;  // DFS order
  std::vector<std::string> frame_names_;
  std::vector<std::string> joint_names_;
  std::vector<std::string> full_joint_names_;
  std::vector<std::string> body_names_;
  std::vector<int> body_root_link_;
  Eigen::MatrixXd mimic_G_;
  Eigen::VectorXd mimic_offset_;
  Eigen::VectorXd joint_lower_, joint_upper_, joint_velocity_, joint_effort_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d(0.0, 0.0, -9.81);
};

}  // namespace mrqp::test
