// The MuJoCo model of a scene, written as MJCF text by our own code (docs/mujoco.md, "How the
// model is built"): each robot from its URDF (parsed with urdfdom) as a body tree placed at the
// scene pose, fixed or on a free joint; rigid objects as free bodies with their mass, centre of
// mass and inertia; the ground plane; collision geometry from the URDF (STL meshes, primitives),
// the reference convex hulls where a link has only COLLADA meshes, and the plant section's
// primitives; contact parameters per pair; grasps as welds.
//
// Names in the model: bodies "ENTITY/LINK" (a rigid object's body "ENTITY/ENTITY"), joints
// "ENTITY/JOINT", free joints "ENTITY/root", geoms "ENTITY/LINK/N". Host-side: allocates, throws
// std::runtime_error with the file and element at fault.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "scene/scene_spec.hpp"
#include "sim/plant_spec.hpp"

namespace mrqp::sim {

/// A URDF mimic joint: q_joint = offset + multiplier · q_master, held by a joint equality of the
/// model (the generated models fold the mimic joint into its master: it is not one of theirs).
struct MjcfMimic {
  std::string joint, master;
  double multiplier = 1.0, offset = 0.0;
};

/// What the writer put into the model for one entity.
struct MjcfEntity {
  std::string name;
  std::string model;      ///< the scene's model name
  bool floating = false;  ///< on a free joint "ENTITY/root"
  bool rigid_object = false;
  std::string root_body;            ///< "ENTITY/LINK" of the root link
  std::vector<std::string> links;   ///< link names (without prefix), bodies of the model
  std::vector<std::string> joints;  ///< moving joint names (without prefix), in model order
  std::vector<MjcfMimic> mimics;    ///< those of `joints` that follow another one
};

/// A grasp: the relative pose of body2 in body1 that a weld holds.
struct MjcfWeld {
  std::string contact;
  std::string body1, body2;                                    ///< prefixed body names
  Eigen::Isometry3d relative = Eigen::Isometry3d::Identity();  ///< pose of body2 in body1
  bool relative_known = false;  ///< false: MuJoCo takes it from the reference configuration
  /// A connect (GraspSpec::Hold::Point): `point` of body2 (its frame) held on body1. MuJoCo 2.2's
  /// connect takes body2's point from the reference configuration: the plant writes `point`
  /// into the model's eq_data after loading (MujocoPlant).
  bool point_only = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

struct MjcfModel {
  std::string xml;
  std::vector<MjcfEntity> entities;
  std::vector<MjcfWeld> welds;
};

/// Writes the model. `welds` are the grasps with their relative poses when known (a second
/// pass, after the initial state is placed: see MujocoPlant); empty: the grasps of the plant
/// section with poses from the reference configuration.
MjcfModel writeMjcf(const scene::SceneSpec& scene, const PlantSpec& plant,
                    const std::vector<MjcfWeld>& welds = {});

}  // namespace mrqp::sim
