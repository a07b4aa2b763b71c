// The validated kinematic tree the generator emits code from: fixed joints merged, bodies in
// depth-first pre-order, mimic joints resolved onto the coordinate they follow.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace mrqp::gen {

/// The element position of a body, frame or coordinate index (an int: -1 means "none", e.g. the
/// root's parent) in the tree's std::vector members; only for indices already known to be >= 0.
inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// Inertia of a body about its own origin, in its own frame: mass, first moment h = m·c and
/// rotational inertia about the origin.
struct BodyInertia {
  double mass = 0.0;
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
};

enum class JointKind { Fixed, Revolute, Prismatic, Floating };

/// The joint that connects a body to its parent body.
struct TreeJoint {
  std::string name;
  JointKind kind = JointKind::Fixed;
  bool continuous = false;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit axis in the body frame
  int q_index = -1;                                 ///< first position coordinate driving this joint
  int v_index = -1;                                 ///< first velocity coordinate driving this joint
  bool mimic = false;
  std::string mimicked;     ///< the independent joint a mimic joint follows
  double multiplier = 1.0;  ///< q_joint = multiplier · q[q_index] + offset
  double offset = 0.0;
  double lower = 0.0, upper = 0.0, velocity = 0.0, effort = 0.0;
  bool has_limits = false;
};

struct TreeBody {
  std::string name;                                  ///< name of the URDF link at the body's origin
  int parent = -1;                                   ///< parent body, -1 for the root
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();  ///< joint frame in the parent body frame
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero();
  TreeJoint joint;
  BodyInertia inertia;
};

/// A named frame: every URDF link, placed on the body it was merged into.
struct TreeFrame {
  std::string name;
  int body = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

enum class ShapeKind { Box, Cylinder, Sphere, ConvexMesh };

struct CollisionShape {
  std::string link;
  int body = 0;
  ShapeKind kind = ShapeKind::Box;
  Eigen::Vector3d size =
      Eigen::Vector3d::Zero();  ///< box: full extents; cylinder: radius, length; sphere: radius
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< shape pose in the body frame
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices;  ///< convex hull vertices (ConvexMesh), shape frame
};

struct KinematicTree {
  std::string robot_name;
  bool floating_base = false;
  int nq = 0;
  int nv = 0;
  std::vector<TreeBody> bodies;
  std::vector<TreeFrame> frames;
  std::vector<CollisionShape> shapes;
  std::vector<std::string> joint_names;  ///< independent joints, v order (after the base)
  std::vector<double> q_lower, q_upper, v_limit, effort_limit;  ///< sized nq, nq, nv, nv
  std::vector<std::string> warnings;

  double totalMass() const {
    double m = 0.0;
    for (const auto& b : bodies) m += b.inertia.mass;
    return m;
  }
};

}  // namespace mrqp::gen
