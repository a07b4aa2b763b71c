// Test helper: emulated device firmware (mrqp_emulation) on a SimNode, and hosts that give each
// device the same ideal physics as the hand-written fakes of fake_devices.hpp, so that a rig with
// the emulated firmware and a rig with the fakes can be compared frame by frame.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulation.hpp>
#include <mrqp/emulation/sim_device_node.hpp>

#include <array>
#include <cstdint>

namespace drvtest {

/// Frames reaching the node go to every device; the node's timer runs their advance().
template <class Device>
using EmulatedNode = mrqp::emulation::SimDeviceNode<Device>;

/// Joints as FakeMitMotors moves them: torque = kp (p_cmd - p) + t_ff, then p = p_cmd when
/// kp > 0, v = v_cmd (float arithmetic, as the fake). `hand` = true: as FakeHandBoard (position
/// mode copies p, v, t; torque mode only t). Frames go out on the node.
class IdealJointHost final : public mrqp::emulation::JointHost {
 public:
  IdealJointHost(mrqp::drivers::SimNode& node, bool hand) : node_(node), hand_(hand) {}
  void emit(const mrqp_fw_frame& frame, mrqp::drivers::TimeNs at) noexcept override {
    (void)node_.sendAt(frame, at);
  }
  mrqp::emulation::JointMeasurement measure(std::size_t j, mrqp::drivers::TimeNs) noexcept override {
    return {static_cast<double>(p[j]), static_cast<double>(v[j]), static_cast<double>(t[j])};
  }
  void command(std::size_t j, const mrqp::emulation::ServoCommand& s,
               mrqp::drivers::TimeNs) noexcept override {
    servo[j] = s;
    ++commands;
    if (!s.enabled) {
      return;
    }
    const auto f = [](double x) { return static_cast<float>(x); };
    if (hand_) {
      if (s.kp > 0.0) {
        p[j] = f(s.position);
        v[j] = f(s.velocity);
      }
      t[j] = f(s.torque);
      return;
    }
    t[j] = f(s.kp) * (f(s.position) - p[j]) + f(s.torque);
    if (s.kp > 0.0) {
      p[j] = f(s.position);
    }
    v[j] = f(s.velocity);
  }

  std::array<float, 64> p{};
  std::array<float, 64> v{};
  std::array<float, 64> t{};
  std::array<mrqp::emulation::ServoCommand, 64> servo{};
  unsigned commands = 0;

 private:
  mrqp::drivers::SimNode& node_;
  bool hand_;
};

class ConstantFtHost final : public mrqp::emulation::EmulatedFtSensor::Host {
 public:
  explicit ConstantFtHost(mrqp::drivers::SimNode& node) : node_(node) {}
  void emit(const mrqp_fw_frame& frame, mrqp::drivers::TimeNs at) noexcept override {
    (void)node_.sendAt(frame, at);
  }
  std::array<double, 6> wrench(mrqp::drivers::TimeNs) noexcept override { return value; }
  std::array<double, 6> value{};

 private:
  mrqp::drivers::SimNode& node_;
};

class ConstantImuHost final : public mrqp::emulation::EmulatedImu::Host {
 public:
  explicit ConstantImuHost(mrqp::drivers::SimNode& node) : node_(node) {}
  void emit(const mrqp_fw_frame& frame, mrqp::drivers::TimeNs at) noexcept override {
    (void)node_.sendAt(frame, at);
  }
  mrqp::emulation::ImuValues imu(mrqp::drivers::TimeNs) noexcept override { return value; }
  mrqp::emulation::ImuValues value{};

 private:
  mrqp::drivers::SimNode& node_;
};

}  // namespace drvtest
