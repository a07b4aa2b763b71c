// The ideal plant: the multi-robot problem's own model as the world (docs/loop.md). Every entity
// integrates the accelerations of the controller's last Optimal solve (semi-implicit Euler, as
// MultiRobotProblem::integrate); a position servo is perfect here: an enabled joint with kp > 0
// is at its commanded position and velocity from the moment the command is applied and holds it until the next. A torque
// command (kp = 0) leaves the joint on the QP's acceleration, which is the one its τ produces in
// the model. The world is a second problem built from the same scene, so the plant's state is
// never the controller's.
//
// The ground is perfect too: a robot's floating base is not left to the open-loop integration of
// its q̈ (its feet would slide: nothing in this world holds them) but follows its ground contacts,
// whose frames stay where they were when each contact became active (the contact-kinematics fit of
// ContactEstimator on the world, all six base coordinates and their twist).
//
// F/T sensors read zero here; an IMU reports its frame's orientation and the root's rates.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "loop/contact_estimator.hpp"
#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::loop {

class IdealPlant final : public Plant {
 public:
  /// `world`: the scene's entities in their initial state (a problem of its own); `model`: the
  /// controller's problem whose last solution moves the world.
  IdealPlant(std::unique_ptr<problem::MultiRobotProblem> world, const problem::MultiRobotProblem& model);

  /// false: the world no longer takes the controller's accelerations (the controller stopped
  /// solving: its last solution must not be applied); unactuated coordinates keep their velocity.
  void setFollowing(bool follow) noexcept { following_ = follow; }

  const char* kind() const noexcept override { return "ideal"; }
  int entityHandle(const std::string& entity) const override;
  int jointHandle(const std::string& entity, const std::string& joint) const override;
  int frameHandle(const std::string& entity, const std::string& frame) const override;

  double jointPosition(int joint) const noexcept override;
  double jointVelocity(int joint) const noexcept override;
  double jointTorque(int joint) const noexcept override;
  void setServo(int joint, const ServoCommand& command) noexcept override;
  Vector6d sensorWrench(int frame) const noexcept override;
  ImuSample imu(int frame) const noexcept override;
  void step(double dt) noexcept override;
  double time() const noexcept override { return time_; }
  void entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                   Eigen::Ref<Eigen::VectorXd> v) const noexcept override;

  /// Fault injection: joint readings become NaN from now on (a broken encoder).
  void breakSensor(int joint) noexcept;

 private:
  static constexpr int kStride = 1024;
  struct Servo {
    ServoCommand cmd;
    bool set = false;
  };
  void applyServo(int joint) noexcept;

  std::unique_ptr<problem::MultiRobotProblem> world_;
  const problem::MultiRobotProblem& model_;
  std::vector<std::vector<Servo>> servos_;  // per entity, per velocity index
  std::vector<std::vector<bool>> broken_;
  Eigen::VectorXd zeros_;
  mutable std::vector<std::uint8_t> tracked_;  // entities whose frames sensors read
  std::unique_ptr<ContactEstimator> ground_;   // floating bases held by their ground contacts
  bool following_ = true;
  double time_ = 0.0;
};

}  // namespace mrqp::loop
