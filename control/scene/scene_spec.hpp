// A scene as written by the user (docs/scenes.md): plain data with names, before they are resolved
// against the models. Every element remembers the line of the YAML file it came from so that an
// error found later (unknown frame, joint out of range) still names file, line and field.
#pragma once

#include <Eigen/Core>

#include <any>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mrqp::scene {

/// Where an element was written: file and 1-based line (0 when built in code).
struct Source {
  std::string file;
  int line = 0;
};

struct PoseSpec {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  /// Roll, pitch, yaw (rad), R = Rz(yaw) Ry(pitch) Rx(roll), as URDF.
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};

struct SpringSpec {
  double stiffness = 0.0;  // K of eq. 48
  double damping = 0.0;    // C
  double offset = 0.0;     // O
  Source source;
};

struct RigidObjectSpec {
  double mass = 1.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();          // in the object frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  // about the CoM, object axes
};

struct EntitySpec {
  std::string name;
  /// A compiled-in generated model ("panda", "jvrc1", "door", ...) or "rigid_object".
  std::string model;
  RigidObjectSpec object;           // when model == "rigid_object"
  PoseSpec pose;                    // floating base: initial pose; fixed base: placement
  std::map<std::string, double> q;  // initial joint positions by joint name (others neutral)
  /// "all" (default for robots), "none" (mechanisms and objects), or a list of joint names.
  std::string actuation = "default";
  std::vector<std::string> actuated_joints;
  std::vector<std::string> passive_joints;
  std::map<std::string, SpringSpec> springs;  // by joint name
  Source source;
};

struct ContactSpec {
  std::string name;
  std::string entity, frame;  // the surface; points and normal are in this frame
  std::string other_entity;   // empty: the fixed environment ("ground")
  std::string other_frame;    // frame of other_entity that carries the reaction
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // direction of the force ON `entity`
  double friction = 0.7;
  int generators = 4;
  /// Directions of the contact frame left free (problem::ContactDirection bits; `free:` words).
  std::uint8_t free = 0;
  bool active = true;
  Source source;
};

struct TaskSpec {
  std::string name;
  std::string type = "posture";                     // the kind's name (task_registry.cpp)
  std::vector<std::string> entities;                // one, or several for a group CoM
  std::string frame;                                // frame tasks
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // frame tasks: controlled point in the frame
  std::string joint;                                // joint target
  std::string contact;                              // force tasks
  double weight = 1.0;
  double stiffness = 10.0;
  std::optional<double> damping;  // default: critical, 2·sqrt(stiffness)
  /// Dimension selector, e.g. {1,1,0} for x and y of a CoM. Empty: all dimensions.
  std::vector<int> dims;
  /// Target: posture (joint name → value, others keep their initial value), CoM/position xyz,
  /// orientation rpy, pose xyz+rpy, joint value, force xyz. Absent: the value at start.
  std::optional<Eigen::VectorXd> target;
  std::map<std::string, double> posture_target;
  bool active = true;
  Source source;
};

/// The CoM support-region damper (paper 2, eq. 7) of one entity, over the convex hull of its
/// contacts with the environment.
struct ComDamperSpec {
  std::string entity;
  double interaction = 0.05;  // d_i, m
  double security = 0.01;     // d_s, m
  double damping = 0.5;       // ξ
  Source source;
};

/// A linear inequality on joint positions kept by a velocity damper: Σ coeff·q ≤ upper
/// (e.g. a door latch: the door cannot open until the handle is turned).
struct JointInequalitySpec {
  std::string name;
  struct Term {
    std::string entity, joint;
    double coeff = 1.0;
  };
  std::vector<Term> terms;
  double upper = 0.0;
  double interaction = 0.05;
  double security = 0.0;
  double damping = 0.5;
  Source source;
};

/// An item of a constraint kind that has no list of its own in SceneSpec (constraint_registry.cpp):
/// the kind's reader stores its own spec type in `spec`, its factory reads it back.
struct ConstraintItemSpec {
  std::string kind;  // the kind's top-level key
  std::string name;  // empty when the kind has no names
  std::any spec;
  Source source;
};

struct SettingsSpec {
  double dt = 0.001;      // control period, s
  double duration = 5.0;  // length of a simulated run, s
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  int max_tasks = 32;                // capacity: tasks that may exist at once
  int max_contacts = 16;             // capacity: contacts that may exist at once
  int max_contact_generators = 256;  // capacity: λ variables in all
  double contact_stiffness = 100.0;  // Baumgarte gains of the no-slip constraints
  double contact_damping = 20.0;
  double regularisation = 1e-6;  // weight on ‖q̈‖² and ‖λ‖² keeping the Hessian definite
  Source source;
};

struct SceneSpec {
  std::string file;
  SettingsSpec settings;
  std::vector<EntitySpec> entities;
  std::vector<ContactSpec> contacts;
  std::vector<TaskSpec> tasks;
  std::vector<ComDamperSpec> com_dampers;
  std::vector<JointInequalitySpec> joint_inequalities;
  std::vector<ConstraintItemSpec> constraints;  // items of every other constraint kind, in file order
};

}  // namespace mrqp::scene
