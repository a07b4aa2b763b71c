// The `plant:` section of a scene file (docs/mujoco.md) as plain data: which simulator runs the
// world, its time step, contact softness and friction (defaults and per pair of entities), the
// collision shapes the models lack (rigid objects, links without a usable mesh), the contacts of
// the scene that the simulator realises as rigid grasps, and the noise and bias of the sensors.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_spec.hpp"

namespace mrqp::sim {

/// Contact parameters of MuJoCo: sliding friction μ and the soft-constraint reference
/// (solref = time constant, damping ratio: smaller timeconst = stiffer contact).
struct ContactParams {
  double friction = 0.8;
  double timeconst = 0.005;  ///< s, ≥ 2 time steps
  double dampratio = 1.0;
};

/// Parameters of the contacts between the geometry of two entities ("ground": the floor).
struct PairSpec {
  std::string a, b;
  bool collide = true;  ///< false: the two never touch (e.g. a hand and the object it grasps)
  ContactParams params;
  scene::Source source;
};

/// A primitive collision shape fixed to a link (or to a rigid object).
struct GeomSpec {
  enum class Type { Box, Sphere, Cylinder, Capsule };
  std::string entity;
  std::string link;  ///< empty: the root (the object frame of a rigid object)
  Type type = Type::Box;
  /// box: full edge lengths x y z; sphere: radius; cylinder and capsule: radius, length (along z).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  scene::PoseSpec pose;  ///< in the link frame
  scene::Source source;
};

/// Gaussian noise and constant bias of one measured quantity (same bias on every component).
struct NoiseSpec {
  double stddev = 0.0;
  double bias = 0.0;
};

struct SensorNoiseSpec {
  NoiseSpec joint_position;  ///< rad
  NoiseSpec joint_velocity;  ///< rad/s
  NoiseSpec joint_torque;    ///< N·m
  NoiseSpec force;           ///< N (F/T sensor)
  NoiseSpec torque;          ///< N·m (F/T sensor)
  NoiseSpec gyro;            ///< rad/s (IMU)
  NoiseSpec accelerometer;   ///< m/s² (IMU)
};

struct PlantSpec {
  bool present = false;             ///< the scene has a plant section
  std::string simulator = "ideal";  ///< "ideal" or "mujoco" (default "mujoco" in a section)
  double timestep = 0.0005;         ///< MuJoCo's step, s
  /// "euler": MuJoCo's semi-implicit Euler, the drives' kd taken implicitly as joint damping
  /// (fast); "implicit": MuJoCo's implicit integrator (every velocity derivative, about three
  /// times slower on a humanoid).
  std::string integrator = "euler";
  ContactParams contact;  ///< every pair without its own entry
  std::vector<PairSpec> pairs;
  std::vector<GeomSpec> geoms;
  std::vector<std::string> grasps;  ///< scene contacts held as rigid welds
  SensorNoiseSpec noise;
  std::uint64_t seed = 1;
  std::vector<std::string> package_path;  ///< where package:// meshes are looked up
  scene::Source source;
};

}  // namespace mrqp::sim
