// The plant as the world of emulated joint actuators (see plant_joint_host.hpp).
#include "loop/plant_joint_host.hpp"

namespace mrqp::loop {

std::size_t PlantJointHost::addJoint(int plant_joint, double torque_limit) {
  joints_.push_back(Joint{plant_joint, torque_limit > 0.0 ? torque_limit : 1e9});
  return joints_.size() - 1;
}

void PlantJointHost::emit(const mrqp_fw_frame& frame, emulation::TimeNs at) noexcept {
  (void)node_.sendAt(frame, at);
}

emulation::JointMeasurement PlantJointHost::measure(std::size_t joint, emulation::TimeNs) noexcept {
  emulation::JointMeasurement m;
  if (joint >= joints_.size()) return m;
  const int h = joints_[joint].handle;
  m.position = plant_.jointPosition(h);
  m.velocity = plant_.jointVelocity(h);
  m.torque = plant_.jointTorque(h);
  return m;
}

void PlantJointHost::command(std::size_t joint, const emulation::ServoCommand& servo,
                             emulation::TimeNs) noexcept {
  if (joint >= joints_.size()) return;
  ServoCommand c;
  c.position = servo.position;
  c.velocity = servo.velocity;
  c.torque = servo.torque;
  c.kp = servo.kp;
  c.kd = servo.kd;
  c.torque_limit = joints_[joint].torque_limit;
  c.enabled = servo.enabled;
  plant_.setServo(joints_[joint].handle, c);
}

}  // namespace mrqp::loop
