// A fake CANopen CiA 402 drive for the driver tests: the emulated drive side of mrqp drivers
// (EmulatedCia402Drive: NMT, SDO server and object dictionary with the CiA 301 rules, the CiA 402
// state machine, RPDO1 / TPDO1 / TPDO2 on SYNC, heartbeat, EMCY) attached to a SimNode as its
// firmware. Its motion echoes the targets: in CSP the position is the target position, in CST
// the torque is the target torque. Answers and TPDOs leave response_delay after the request /
// SYNC. Allocation-free after construction.
#pragma once

#include <mrqp/firmware_if/firmware_if.h>
#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_cia402_drive.hpp>

#include <cstdint>

namespace drvtest {

using mrqp::drivers::RxFrame;
using mrqp::drivers::SimNode;
using mrqp::drivers::TimeNs;

struct FakeDriveOptions {
  std::uint8_t node = 1;
  TimeNs boot_delay = 2000000;    ///< reset -> boot-up message (2 ms)
  TimeNs response_delay = 20000;  ///< SDO answer / TPDO after SYNC (20 us)
  std::int32_t initial_position = 0;
  mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  mrqp::emulation::VendorProfile profile = mrqp::emulation::VendorProfile::lenient();
};

class FakeCia402Drive final : public mrqp::drivers::SimListener,
                              private mrqp::emulation::EmulatedCia402Drive::Host {
 public:
  FakeCia402Drive(SimNode& node, const FakeDriveOptions& options);

  void onReceive(SimNode& node, mrqp::drivers::ReceiveResult kind, const RxFrame& rx) noexcept override;
  void onTransmitted(SimNode& node, const mrqp_fw_frame& frame, TimeNs end) noexcept override;
  void onTimer(SimNode& node, TimeNs now) noexcept override;

  // ---- test controls ----
  /// Power off (disconnects the node: no frames, no ACK) / on (boots again).
  void power(bool on) noexcept;
  /// A fault: EMCY with `code`, then Fault reaction active -> Fault at the next SYNC.
  void injectFault(std::uint16_t code, std::uint8_t error_register) noexcept;
  /// Stop sending TPDOs (heartbeat continues).
  void setPdoSilent(bool silent) noexcept { drive_.setPdoSilent(silent); }
  /// No frame at all / the next n TPDOs one byte short (the emulated drive's fault switches).
  void setSilent(bool silent) noexcept { drive_.setSilent(silent); }
  void corruptPdos(unsigned n) noexcept { drive_.corruptPdos(n); }
  /// Answer SDO writes to index:sub with an abort.
  void abortOnWrite(std::uint16_t index, std::uint8_t sub, std::uint32_t code) noexcept {
    drive_.abortOnWrite(index, sub, code);
  }
  /// Report this mode in the mode display instead of 0x6060.
  void forceModeDisplay(std::int8_t mode) noexcept { drive_.forceModeDisplay(mode); }

  // ---- observation ----
  mrqp_fw_nmt_state nmt() const noexcept { return drive_.nmt(); }
  mrqp_fw_cia402_state state() const noexcept { return drive_.state(); }
  bool od(std::uint16_t index, std::uint8_t sub, std::uint32_t* value) const noexcept {
    return drive_.od(index, sub, value);
  }
  std::int32_t targetPosition() const noexcept { return drive_.targetPosition(); }
  std::int16_t targetTorque() const noexcept { return drive_.targetTorque(); }
  std::int32_t position() const noexcept { return position_; }
  std::uint16_t lastControlword() const noexcept { return drive_.lastControlword(); }
  unsigned sdoWrites() const noexcept { return drive_.sdoWrites(); }
  unsigned syncs() const noexcept { return drive_.syncs(); }
  bool tpdo1Configured() const noexcept { return drive_.tpdo1Configured(); }
  bool tpdo2Configured() const noexcept { return drive_.tpdo2Configured(); }
  bool rpdo1Configured() const noexcept { return drive_.rpdo1Configured(); }
  unsigned commErrors() const noexcept { return drive_.commErrors(); }
  bool commErrorActive() const noexcept { return drive_.commErrorActive(); }

 private:
  using Drive = mrqp::emulation::EmulatedCia402Drive;
  void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept override;
  void onNmtReset(bool application) noexcept override;
  Drive::Feedback onSync(const Drive& drive, bool new_targets, TimeNs now) noexcept override;
  void rearm() noexcept;

  SimNode& node_;
  Drive drive_;
  bool powered_ = true;
  std::int32_t position_ = 0;
  std::int32_t velocity_ = 0;
  std::int16_t torque_ = 0;
};

}  // namespace drvtest
