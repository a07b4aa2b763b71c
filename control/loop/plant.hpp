// The world the controller acts on, behind one interface: the ideal plant (the multi-robot
// problem's own accelerations integrated: every servo perfect) and the MuJoCo plant (a physics
// simulation with its own contacts and friction). The emulated firmware on the bus (drives, F/T
// sensors, IMUs) reads and actuates the plant through this interface; the controller never does:
// it sees only CAN frames.
//
// Set-up (names → handles) may allocate and throw; everything else is noexcept and allocation-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

namespace mrqp::loop {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// What the actuator of one joint is told, as a drive's current loop would apply it every plant
/// step: τ = clamp(τ_ff + kp (q_ref − q) + kd (v_ref − v), ±torque_limit). A CSP drive sets
/// kp, kd > 0; a CST drive kp = kd = 0 and τ_ff; an MIT-mode motor its commanded impedance.
struct ServoCommand {
  double position = 0.0;      ///< q_ref, rad (or m for a prismatic joint)
  double velocity = 0.0;      ///< v_ref
  double torque = 0.0;        ///< τ_ff, N·m
  double kp = 0.0;            ///< N·m/rad
  double kd = 0.0;            ///< N·m·s/rad
  double torque_limit = 1e9;  ///< N·m, > 0
  bool enabled = false;       ///< false: no torque (the drive is off)
};

/// An inertial measurement unit fixed to a frame: orientation of the frame in the world,
/// angular velocity and specific force (acceleration minus gravity) in the frame's axes.
struct ImuSample {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force = Eigen::Vector3d::Zero();
};

class Plant {
 public:
  virtual ~Plant() = default;
  /// "ideal" or "mujoco".
  virtual const char* kind() const noexcept = 0;
  /// Whether the emulated position drives ramp to each cyclic setpoint over its period (and so
  /// report the previous setpoint's velocity at the SYNC) rather than reach it at once: what a
  /// robot's `interpolating_drives` declares of real drives (docs/loop.md), true of a simulated
  /// bus only where the plant's drives do it.
  virtual bool drivesInterpolate() const noexcept { return false; }

  // ---- set-up: scene names → handles (−1 when the plant has no such thing) ----
  virtual int entityHandle(const std::string& entity) const = 0;
  virtual int jointHandle(const std::string& entity, const std::string& joint) const = 0;
  virtual int frameHandle(const std::string& entity, const std::string& frame) const = 0;

  // ---- what the emulated firmware reads and applies (real-time) ----
  virtual double jointPosition(int joint) const noexcept = 0;
  virtual double jointVelocity(int joint) const noexcept = 0;
  /// The torque the joint's actuator applied over the last step (a drive's current sensor).
  virtual double jointTorque(int joint) const noexcept = 0;
  /// Holds until changed; applied at every internal step of step().
  virtual void setServo(int joint, const ServoCommand& command) noexcept = 0;
  /// A force/torque sensor at `frame`: the wrench (force; moment about the frame origin), in the
  /// frame's axes, that the sensor's distal side (hand, tool, held object) exerts on its proximal
  /// side — what a wrist sensor measures, before noise and bias.
  virtual Vector6d sensorWrench(int frame) const noexcept = 0;
  virtual ImuSample imu(int frame) const noexcept = 0;

  /// Advances the world by dt under the current servo commands.
  virtual void step(double dt) noexcept = 0;
  /// Simulated time since the start, s.
  virtual double time() const noexcept = 0;

  // ---- ground truth for logs and summaries (never read by the controller) ----
  /// The state of an entity in the problem's convention (q = [p; w x y z; joints] for a floating
  /// base, v = (ω; v) body twist then joint rates; entity.nq() / nv() sizes).
  virtual void entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                           Eigen::Ref<Eigen::VectorXd> v) const noexcept = 0;
};

}  // namespace mrqp::loop
