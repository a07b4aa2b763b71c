// A plant for tests whose entity states are set by hand (loop::Plant): each entity's q and v are
// what the test wrote, everything else is inert (no joint, frame, sensor or servo; time stands
// still). For code that reads the plant's ground truth (entityState), e.g. mrqp-run's watches of a
// scene's outcome, checked against states given in closed form.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::testing {

class SetStatePlant final : public loop::Plant {
 public:
  SetStatePlant() = default;
  /// One entity per entity of `p`, in its order, at its current q, at rest.
  explicit SetStatePlant(const problem::MultiRobotProblem& p);

  /// Adds an entity at state `q`, at rest (its v reads zero); returns its handle.
  int add(const std::string& name, const Eigen::VectorXd& q);
  /// An entity with `nv` velocity coordinates (the problem's convention).
  int add(const std::string& name, const Eigen::VectorXd& q, Eigen::Index nv);

  Eigen::VectorXd& q(int entity) { return q_.at(static_cast<std::size_t>(entity)); }
  Eigen::VectorXd& v(int entity) { return v_.at(static_cast<std::size_t>(entity)); }
  /// A floating base's pose: q = [p; w x y z; ...].
  void place(int entity, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation);

  const char* kind() const noexcept override { return "set-state"; }
  int entityHandle(const std::string& entity) const override;
  int jointHandle(const std::string&, const std::string&) const override { return -1; }
  int frameHandle(const std::string&, const std::string&) const override { return -1; }
  double jointPosition(int) const noexcept override { return 0.0; }
  double jointVelocity(int) const noexcept override { return 0.0; }
  double jointTorque(int) const noexcept override { return 0.0; }
  void setServo(int, const loop::ServoCommand&) noexcept override {}
  loop::Vector6d sensorWrench(int) const noexcept override { return loop::Vector6d::Zero(); }
  loop::ImuSample imu(int) const noexcept override { return {}; }
  void step(double) noexcept override {}
  double time() const noexcept override { return 0.0; }
  void entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                   Eigen::Ref<Eigen::VectorXd> v) const noexcept override;

 private:
  std::vector<std::string> names_;
  std::vector<Eigen::VectorXd> q_, v_;
};

}  // namespace mrqp::testing
