// The MuJoCo plant (docs/mujoco.md): the scene's world simulated by MuJoCo 2.2 from Debian behind
// the loop's Plant interface. Robots, objects and mechanisms are bodies of one MuJoCo model written
// from the scene (mjcf_writer.hpp); contacts and friction are MuJoCo's. Each joint's actuator is the
// drive's current loop, applied at every MuJoCo step:
//   τ = clamp(τ_ff + kp (q_ref − q) + kd (v_ref − v), ±torque_limit),
// as a MuJoCo actuator with an affine bias; the drive's damping is taken implicitly by the
// integrator (as joint damping with semi-implicit Euler, in the actuator with MuJoCo's implicit
// integrator), so stiff drives stay stable at the plant's step. The plant section's `drives` add what a
// real drive's firmware does between cyclic setpoints: linear interpolation of the position
// reference and integral action; `settle` starts the world at rest (docs/mujoco.md). With Euler the −kd q̇ part is
// outside the clamp. The scene's joint springs
// −(K q + C q̇ + O) act on their joints; grasps of the plant section are welds; URDF mimic joints
// follow their master through joint equalities.
//
// Conventions of the queries (plant.hpp): a floating entity's q = [p; w x y z; joints] and
// v = (ω; v) body twist in the root-link frame, then the joint rates (MuJoCo's free joint has its
// linear velocity in the world frame: converted here). sensorWrench: the wrench the subtree of the
// frame's body (and everything it grasps) exerts on its parent, moment about the frame origin, in
// the frame's axes; a marker frame (a link that carries nothing: no mass, geometry or weld in its
// subtree) measures across its nearest ancestor that carries something, as a wrist sensor does
// (a weld's torque taken as transmitted, not as MuJoCo 2.2's cfrc_ext counts it: mujoco_plant.cpp). imu: specific force (acceleration − gravity) and angular velocity in the
// frame's axes.
//
// Real-time: step() and every query are noexcept and allocation-free (mj_step works in mjData's
// preallocated stack); construction allocates and throws std::runtime_error.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "loop/plant.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_spec.hpp"
#include "sim/mjcf_writer.hpp"
#include "sim/plant_spec.hpp"
#include "sim/sensor_noise.hpp"

namespace mrqp::sim {

class MujocoPlant final : public loop::Plant {
 public:
  /// Builds the model of `scene` with the parameters of `plant` and places the initial state
  /// (scene poses and joint values). With `registry`, each robot's joint order and neutral
  /// configuration are its generated model's (entityState then matches the problem's entity);
  /// without, the joints are in MuJoCo's order and start at 0 (within their limits).
  MujocoPlant(const scene::SceneSpec& scene, const PlantSpec& plant,
              const scene::ModelRegistry* registry = nullptr);
  ~MujocoPlant() override;
  MujocoPlant(const MujocoPlant&) = delete;
  MujocoPlant& operator=(const MujocoPlant&) = delete;

  const char* kind() const noexcept override { return "mujoco"; }
  /// The plant section's `drives.interpolate`.
  bool drivesInterpolate() const noexcept override { return drives_.interpolate; }

  int entityHandle(const std::string& entity) const override;
  int jointHandle(const std::string& entity, const std::string& joint) const override;
  /// A frame is a link of a robot (a body of the model), or the object frame of a rigid object;
  /// its handle is the MuJoCo body id.
  int frameHandle(const std::string& entity, const std::string& frame) const override;

  double jointPosition(int joint) const noexcept override;
  double jointVelocity(int joint) const noexcept override;
  double jointTorque(int joint) const noexcept override;
  void setServo(int joint, const loop::ServoCommand& command) noexcept override;
  loop::Vector6d sensorWrench(int frame) const noexcept override;
  loop::ImuSample imu(int frame) const noexcept override;

  /// round(dt / timestep) MuJoCo steps (at least one), then the state's derived quantities
  /// (sensors, contact and weld forces) at the new state.
  void step(double dt) noexcept override;
  double time() const noexcept override;

  void entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                   Eigen::Ref<Eigen::VectorXd> v) const noexcept override;
  /// Sets an entity's state in the same convention (a test's or a program's initial state; the
  /// quaternion is normalised) and recomputes the derived quantities. Not for the cycle.
  void setEntityState(int entity, const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& v) noexcept;
  /// Sizes of entityState's vectors.
  int entityNq(int entity) const noexcept;
  int entityNv(int entity) const noexcept;
  /// MuJoCo's warnings since the start (too many contacts or constraints, a bad number in the
  /// state that made MuJoCo reset it, ...): a run with any is not to be trusted. MuJoCo's own
  /// printing of warnings is silenced (it would write to stdout from the cycle): read them here.
  int warnings() const noexcept;
  /// World pose of a frame (ground truth, for logs and rendering).
  Eigen::Isometry3d framePose(int frame) const noexcept;

  // ---- MuJoCo itself (host-side: tests, rendering) ----
  const mjModel* model() const noexcept { return model_; }
  const mjData* data() const noexcept { return data_; }
  /// MuJoCo's velocity index (dof) of a joint handle.
  int jointDof(int joint) const noexcept { return joints_[static_cast<std::size_t>(joint)].dof; }
  /// The model's MJCF text and what it holds per entity.
  const MjcfModel& mjcf() const noexcept { return mjcf_; }
  double timestep() const noexcept;

 private:
  struct Joint {
    int qpos = 0, dof = 0, actuator = -1;
    loop::ServoCommand command;
    // The drive's interpolator (PlantSpec::drives.interpolate): the position reference reaches
    // command.position at MuJoCo time ramp_end, moving at command.velocity until then.
    double ramp_end = 0.0;
    double integral_torque = 0.0;  // the drive's integral action, N·m
    bool actuated = false;         // the scene's actuation: a drive holds the joint
    double effort = 1e9;           // the model's effort limit, N·m
    double spring_k = 0.0, spring_c = 0.0, spring_o = 0.0;
  };
  struct Entity {
    std::string name;
    bool floating = false;
    int free_qpos = -1, free_dof = -1, root_body = -1;
    std::vector<int> joints;                          // handles, in the entity's order
    std::vector<std::pair<std::string, int>> frames;  // frame name → body
  };
  struct Mimic {  // a URDF mimic joint, held to its master by a joint equality
    int qpos = 0, dof = 0, master_qpos = 0, master_dof = 0;
    double multiplier = 1.0, offset = 0.0;
  };

  void load(const std::string& xml);
  void placeInitialState(const scene::SceneSpec& scene, const scene::ModelRegistry* registry);
  /// The drives' law on every actuator; `integrate`: inside a MuJoCo step (the integral action
  /// advances by one time step).
  void applyServos(bool integrate) noexcept;
  /// PlantSpec::settle: every actuated joint held at its initial value, the rest free.
  void settle(double duration);
  void placeMimics() noexcept;
  void updateDerived() noexcept;

  MjcfModel mjcf_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<Joint> joints_;
  std::vector<Entity> entities_;
  std::vector<Mimic> mimics_;
  std::vector<int> sensor_body_;  // per body: the body whose subtree a sensor there measures
  DriveSpec drives_;
  /// The plant section's F/T noise and bias, applied to every sensorWrench (seeded: deterministic).
  mutable SensorNoise ft_noise_;
};

}  // namespace mrqp::sim
