// The ideal plant (see ideal_plant.hpp).
#include "loop/ideal_plant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrqp::loop {

IdealPlant::IdealPlant(std::unique_ptr<problem::MultiRobotProblem> world,
                       const problem::MultiRobotProblem& model)
    : world_(std::move(world)), model_(model) {
  if (!world_ || world_->entityCount() != model_.entityCount()) {
    throw std::invalid_argument("ideal plant: the world and the model must hold the same entities");
  }
  for (int e = 0; e < world_->entityCount(); ++e) {
    const auto nv = static_cast<std::size_t>(world_->entity(e).nv());
    servos_.emplace_back(nv);
    broken_.emplace_back(nv, false);
  }
  int max_nv = 0;
  for (int e = 0; e < world_->entityCount(); ++e) max_nv = std::max(max_nv, world_->entity(e).nv());
  zeros_ = Eigen::VectorXd::Zero(max_nv);
  tracked_.assign(static_cast<std::size_t>(world_->entityCount()), 0);
  // The robots' floating bases on a perfect ground (objects and mechanisms keep their integration).
  std::vector<bool> robot(static_cast<std::size_t>(world_->entityCount()), false);
  bool any = false;
  for (int e = 0; e < world_->entityCount(); ++e) {
    const problem::Entity& en = world_->entity(e);
    bool actuated = false;
    for (int k = 0; k < en.nv(); ++k) actuated = actuated || en.actuated()[static_cast<std::size_t>(k)];
    robot[static_cast<std::size_t>(e)] = actuated;
    any = any || (actuated && en.floatingBase());
  }
  if (any) {
    ground_ = std::make_unique<ContactEstimator>(
        *world_, robot, std::vector<int>(static_cast<std::size_t>(world_->entityCount()), -1), 2, false);
  }
}

int IdealPlant::entityHandle(const std::string& entity) const { return world_->entityIndex(entity); }

int IdealPlant::jointHandle(const std::string& entity, const std::string& joint) const {
  const int e = world_->entityIndex(entity);
  if (e < 0) return -1;
  const int k = world_->entity(e).jointIndex(joint);
  return k < 0 ? -1 : e * kStride + k;
}

int IdealPlant::frameHandle(const std::string& entity, const std::string& frame) const {
  const int e = world_->entityIndex(entity);
  if (e < 0) return -1;
  const int f = world_->entity(e).frameIndex(frame);
  if (f >= 0) {
    // A sensor will read this frame: keep the entity's kinematics current.
    tracked_[static_cast<std::size_t>(e)] = 1;
    world_->entity(e).updateKinematics();
  }
  return f < 0 ? -1 : e * kStride + f;
}

double IdealPlant::jointPosition(int joint) const noexcept {
  const int e = joint / kStride, k = joint % kStride;
  if (broken_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)])
    return std::numeric_limits<double>::quiet_NaN();
  const problem::Entity& en = world_->entity(e);
  return en.q()(en.qIndexOfV(k));
}

double IdealPlant::jointVelocity(int joint) const noexcept {
  const int e = joint / kStride, k = joint % kStride;
  if (broken_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)])
    return std::numeric_limits<double>::quiet_NaN();
  return world_->entity(e).v()(k);
}

double IdealPlant::jointTorque(int joint) const noexcept {
  const int e = joint / kStride, k = joint % kStride;
  const Servo& s = servos_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
  if (s.set && s.cmd.enabled && s.cmd.kp == 0.0 && s.cmd.kd == 0.0) return s.cmd.torque;
  return following_ ? model_.torque(e)(k) : 0.0;
}

void IdealPlant::applyServo(int joint) noexcept {
  const int e = joint / kStride, k = joint % kStride;
  const Servo& s = servos_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
  if (!s.set || !s.cmd.enabled || !(s.cmd.kp > 0.0) || !std::isfinite(s.cmd.position) ||
      !std::isfinite(s.cmd.velocity)) {
    return;
  }
  problem::Entity& en = world_->entity(e);
  en.q()(en.qIndexOfV(k)) = s.cmd.position;
  en.v()(k) = s.cmd.velocity;
}

void IdealPlant::setServo(int joint, const ServoCommand& command) noexcept {
  const int e = joint / kStride, k = joint % kStride;
  Servo& s = servos_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
  s.cmd = command;
  s.set = true;
  applyServo(joint);  // a perfect position servo: there at once
}

Vector6d IdealPlant::sensorWrench(int) const noexcept { return Vector6d::Zero(); }

ImuSample IdealPlant::imu(int frame) const noexcept {
  // The frame's orientation; its rate and specific force as the root's (a frame fixed to the
  // root link: the case of a pelvis IMU), the acceleration of the root neglected.
  const problem::Entity& en = world_->entity(frame / kStride);
  const problem::Pose pose = en.framePose(frame % kStride);
  ImuSample s;
  s.orientation = Eigen::Quaterniond(pose.R);
  Eigen::Matrix3d R_root = en.basePose().R;
  if (en.floatingBase()) {
    const auto q = en.q();
    R_root = Eigen::Quaterniond(q(3), q(4), q(5), q(6)).toRotationMatrix();
    s.angular_velocity = pose.R.transpose() * (R_root * en.v().head<3>());
  }
  s.specific_force = -(pose.R.transpose() * world_->settings().gravity);
  return s;
}

void IdealPlant::step(double dt) noexcept {
  for (int e = 0; e < world_->entityCount(); ++e) {
    problem::Entity& en = world_->entity(e);
    if (following_) {
      en.integrate(model_.acceleration(e), dt);
    } else {
      // Stopped: velocities of coordinates without a position servo decay to rest at once.
      for (int k = 0; k < en.nv(); ++k) {
        const Servo& s = servos_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
        if (!(s.set && s.cmd.enabled && s.cmd.kp > 0.0)) en.v()(k) = 0.0;
      }
      en.integrate(zeros_.head(en.nv()), dt);
    }
    // A perfect position servo holds its last target between two commands.
    for (int k = 0; k < en.nv(); ++k) applyServo(e * kStride + k);
    if (tracked_[static_cast<std::size_t>(e)]) en.updateKinematics();
  }
  if (ground_) ground_->estimate();
  time_ += dt;
}

void IdealPlant::entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                             Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  q = world_->entity(entity).q();
  v = world_->entity(entity).v();
}

void IdealPlant::breakSensor(int joint) noexcept {
  broken_[static_cast<std::size_t>(joint / kStride)][static_cast<std::size_t>(joint % kStride)] = true;
}

}  // namespace mrqp::loop
