// One emulated CiA 402 drive on a simulated bus, moving a joint of the plant (docs/loop.md): the
// drive-side protocol of drivers/ (EmulatedCia402Drive) as the firmware of a SimNode, whose motion
// is the plant's joint. At every SYNC in Operation enabled the drive applies its target to the
// plant through Plant::setServo — CSP: a position servo with gains kp, kd and the velocity of its
// targets (Δtarget / cycle) as feed-forward, the RPDO torque as feed-forward torque; CST: the
// target torque — and its TPDOs then sample the plant's joint. Quick stop active: the servo holds
// the position where the quick stop began, with damping. Other states (and before the drive is
// started): the holding brake holds the joint where it was when the brake closed.
//
// Fault injection (the firmware's own faults, never the controller's): a heartbeat that stops, a
// fraction of frames not sent (deterministic), corrupt TPDOs, an encoder that reads NaN (the
// firmware raises EMCY 0x7305, incremental sensor fault). Allocation-free after construction.
#pragma once

#include <mrqp/drivers/emulated_cia402_drive.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <cstdint>

#include "loop/plant.hpp"

namespace mrqp::loop {

struct PlantDriveOptions {
  std::uint8_t node = 1;
  int joint = -1;               ///< plant joint handle
  bool torque_mode = false;     ///< CST (else CSP)
  double rated_torque = 100.0;  ///< N·m per 1000 ‰
  double kp = 20000.0;          ///< CSP servo, N·m/rad
  double kd = 300.0;            ///< N·m·s/rad
  double torque_limit = 1e9;    ///< N·m
  double brake_kp = 20000.0;    ///< holding brake (drive not enabled), as a stiff servo
  double brake_kd = 300.0;
  drivers::TimeNs response_delay = 20000;
  emulation::VendorProfile profile = emulation::VendorProfile::lenient();  ///< how strict the firmware is
};

class PlantCia402Drive final : public drivers::SimListener, private drivers::EmulatedCia402Drive::Host {
 public:
  PlantCia402Drive(drivers::SimNode& node, Plant& plant, const PlantDriveOptions& options);

  void onReceive(drivers::SimNode& node, drivers::ReceiveResult kind,
                 const drivers::RxFrame& rx) noexcept override;
  void onTimer(drivers::SimNode& node, drivers::TimeNs now) noexcept override;

  // ---- fault injection ----
  /// The heartbeat exchange is lost: the drive's heartbeat stops from `at` and the controller's no
  /// longer reaches it (a drive watching it, per 0x1016 and its profile, then reacts by itself).
  void stopHeartbeat(drivers::TimeNs at) noexcept {
    drive_.stopHeartbeatAt(at);
    drive_.setMasterHeartbeatLost(true);
  }
  /// Drop `per_mille` ‰ of the frames this drive sends (a deterministic sequence).
  void setFrameLoss(unsigned per_mille) noexcept { loss_per_mille_ = per_mille; }
  /// Send every TPDO with a wrong length from now on.
  void setCorruptFrames(bool on) noexcept { corrupt_ = on; }
  /// The encoder reads NaN from now on.
  void breakEncoder() noexcept { encoder_broken_ = true; }

  std::uint8_t node() const noexcept { return drive_.node(); }
  mrqp_fw_cia402_state state() const noexcept { return drive_.state(); }
  /// The emulated firmware (observation: NMT state, object dictionary, error counters).
  const drivers::EmulatedCia402Drive& firmware() const noexcept { return drive_; }
  drivers::EmulatedCia402Drive& firmware() noexcept { return drive_; }
  unsigned framesDropped() const noexcept { return dropped_; }

 private:
  using Drive = drivers::EmulatedCia402Drive;
  void emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept override;
  void onNmtReset(bool application) noexcept override;
  Drive::Feedback onSync(const Drive& drive, bool new_targets, drivers::TimeNs now) noexcept override;
  void rearm() noexcept;
  void engageBrake() noexcept;

  drivers::SimNode& node_;
  Plant& plant_;
  PlantDriveOptions options_;
  mrqp_fw_arm_scale scale_{};
  Drive drive_;
  bool have_last_target_ = false;
  double last_target_ = 0.0;
  bool stopping_ = false;
  bool braked_ = false;
  double stop_position_ = 0.0;
  unsigned loss_per_mille_ = 0;
  std::uint32_t rng_ = 0x12345678u;
  unsigned dropped_ = 0;
  bool corrupt_ = false;
  bool encoder_broken_ = false;
  bool encoder_fault_sent_ = false;
};

}  // namespace mrqp::loop
