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
  /// true: the link's own collision geometry (URDF shapes, meshes, reference hulls) is left out
  /// and the link collides with the plant section's shapes only (e.g. a foot sole that matches
  /// the scene's contact surface).
  bool replace = false;
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

/// What the emulated drives' inner loop adds to the servo law of a command (docs/mujoco.md,
/// "Drives"), as the firmware of a real position drive does it between two cyclic setpoints.
struct DriveSpec {
  /// s: integral action of the position servo (ki = kp / integral_time, the integrated torque
  /// clamped to the torque limit): no steady-state error under a constant load (gravity); 0: none.
  double integral_time = 0.0;
  /// Linear interpolation of cyclic setpoints: a command whose velocity is the rate of its
  /// position since the previous one (CSP: Δtarget / SYNC period) ramps the reference from the
  /// previous position to the new one over that period instead of a step.
  bool interpolate = false;
  double hold_kp = 20000.0;  ///< N·m/rad: the holding servo of the settling (see PlantSpec::settle)
  double hold_kd = 300.0;    ///< N·m·s/rad
};

/// A scene contact that the plant holds by a MuJoCo equality between the bodies of its two
/// frames (docs/mujoco.md, "Grasps"). A plain name in `grasps` is a 6-DOF weld with the section's
/// `grasp_softness`; the map form sets, per grasp, what is held and how soft it is.
struct GraspSpec {
  enum class Hold {
    Pose,  ///< a weld: the relative pose of the two bodies
    Point  ///< a connect: one point of each body kept together, the rotation about it free (a
           ///< pinch that lets a lever turn between the pads)
  };
  std::string contact;
  Hold hold = Hold::Pose;
  /// The held point in the contact's frame (the body of the contact's `frame`); a weld with
  /// `point` holds its pose about that point (MuJoCo's `anchor`). Unset: the frame's origin
  /// (a Point grasp needs it).
  bool point_given = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double timeconst = 0.02;  ///< solref, s (default: the section's grasp_softness)
  double dampratio = 1.0;
  scene::Source source;
};

struct PlantSpec {
  bool present = false;             ///< the scene has a plant section
  std::string simulator = "ideal";  ///< "ideal" or "mujoco" (default "mujoco" in a section)
  double timestep = 0.0005;         ///< MuJoCo's step, s
  /// "euler": MuJoCo's semi-implicit Euler, the drives' kd taken implicitly as joint damping
  /// (fast); "implicit": MuJoCo's implicit integrator (every velocity derivative, about three
  /// times slower on a humanoid).
  std::string integrator = "euler";
  DriveSpec drives;
  /// s of simulation before t = 0 with every actuated joint held at its initial value by a
  /// holding servo (drives.hold_kp, hold_kd and the drives' integral action) and every free body and
  /// floating base settling on its contacts; the clock then restarts at 0. 0: none.
  double settle = 0.0;
  ContactParams contact;  ///< every pair without its own entry
  std::vector<PairSpec> pairs;
  std::vector<GeomSpec> geoms;
  std::vector<GraspSpec> grasps;  ///< scene contacts held as welds
  /// Softness of the grasps' welds (MuJoCo's solref of an equality: time constant, damping
  /// ratio; MuJoCo's default 0.02 s, 1): a hand's pads and fingers are not rigid. The default of
  /// every grasp that does not set its own.
  double grasp_timeconst = 0.02;
  double grasp_dampratio = 1.0;
  SensorNoiseSpec noise;
  std::uint64_t seed = 1;
  std::vector<std::string> package_path;  ///< where package:// meshes are looked up
  scene::Source source;
};

}  // namespace mrqp::sim
