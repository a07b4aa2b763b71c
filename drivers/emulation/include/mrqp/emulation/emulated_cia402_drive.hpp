// mrqp emulation -- the drive side of the CiA 402 arm protocol: one emulated drive's firmware.
//
// One CANopen node built from the firmware_if drive-side state machines: NMT (reset node /
// communication, start, stop, pre-operational) with the boot-up message and the heartbeat
// producer (0x1017); an expedited SDO server over a small object dictionary with CiA 301 default
// values and rules (PDO mapping only while the PDO is disabled and its entry count is 0, sizes and
// access checked); the CiA 402 power state machine (mrqp_fw_cia402_drive_next / drive_event);
// RPDO1 applied and TPDO1/TPDO2 sent on SYNC only when configured exactly as the mrqp contract
// maps them; EMCY on faults and "error reset" when a fault is reset.
//
// It is transport-free: frames come in through onFrame(), time moves through advance(), and
// frames go out through the Host, which also supplies the motion behind the state machine (what
// the TPDOs report). The test fakes of tests/drivers put it on a SimNode, mrqp-drive-emu
// (tools/drive_emu) runs one per node id with a physical joint model, the controller loop's plant
// one per drive of a robot. No allocation. Part of mrqp_emulation, not of the runtime drivers.
//
// How strict it is comes from Options::profile (vendor_profile.hpp): the number of TPDOs, SDO aborts
// for absent / read-only / out-of-range objects, the PDO rules, the RTR bit check, a SYNC timeout
// with EMCY 0x8100 and the error behaviour of 0x1029, statusword bits 4 and 9, identity 0x1018
// and device type 0x1000. VendorProfile::lenient() (the default) is the behaviour it always had.
//
// Fault switches (off by default; with all off the drive behaves exactly as before they existed):
// stopHeartbeatAt(), setPdoSilent() (no TPDOs: feedback missing), setSilent() (no frame at
// all: no heartbeat, no SDO answer, no PDO, no EMCY), corruptPdos(n) (the next n TPDOs one byte
// short), raiseFault() (EMCY and the CiA 402 Fault state), setMasterHeartbeatLost() (the
// master's heartbeats no longer reach the drive: its heartbeat consumer, where the profile watches
// 0x1016, times out and the drive reacts as the profile says).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/emulation/vendor_profile.hpp"
#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/cia402.h"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/nmt.h"

namespace mrqp::emulation {

using drivers::TimeNs;

class EmulatedCia402Drive {
 public:
  static constexpr TimeNs kNever = INT64_MAX;

  struct Options {
    std::uint8_t node = 1;        ///< CANopen node id 1..127
    TimeNs boot_delay = 2000000;  ///< reset -> boot-up message (2 ms)
    TimeNs response_delay =
        0;  ///< SDO answer, TPDOs and error reset: ready this long after the request / SYNC
    VendorProfile profile = VendorProfile::lenient();  ///< how strict the drive is
  };

  /// What the TPDOs report, in wire units.
  struct Feedback {
    std::int32_t position = 0;  ///< increments
    std::int32_t velocity = 0;  ///< increments / s
    std::int16_t torque = 0;    ///< per mille of the rated torque
  };

  /// The drive's surroundings: the way out for its frames and the motion behind the state machine.
  class Host {
   public:
    /// A frame of the drive, ready for the bus at `at`.
    virtual void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept = 0;
    /// NMT reset node (`application`) or reset communication, once the drive has been reset.
    virtual void onNmtReset(bool application) noexcept;
    /// A SYNC in Operational, after the state machine took this cycle's RPDO (`new_targets`
    /// when there was one): moves the motion on and returns what the TPDOs report.
    virtual Feedback onSync(const EmulatedCia402Drive& drive, bool new_targets, TimeNs now) noexcept = 0;

   protected:
    ~Host() = default;
  };

  /// What a received frame was to this drive.
  enum class Received : std::uint8_t { Nothing = 0, Nmt, Sdo, Sync, Rpdo };

  /// Powers on: initialisation, then the boot-up message at time options.boot_delay.
  EmulatedCia402Drive(Host& host, const Options& options) noexcept;
  EmulatedCia402Drive(const EmulatedCia402Drive&) = delete;
  EmulatedCia402Drive& operator=(const EmulatedCia402Drive&) = delete;

  /// A frame on the bus at `now` (call advance(now) first when events may be due).
  Received onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  /// The end of the boot and the heartbeat, when due at or before `now`.
  void advance(TimeNs now) noexcept;
  /// The next time advance() has something to do, kNever if none.
  TimeNs nextEvent() const noexcept;

  // ---- power and fault injection ----
  /// Power on again: the object dictionary and the state machines restart, boot-up after the boot delay.
  void powerOn(TimeNs now) noexcept;
  /// A fault: EMCY with `code` at `now`, Fault reaction active, then Fault at the next SYNC.
  void raiseFault(std::uint16_t code, std::uint8_t error_register, TimeNs now) noexcept;
  /// No heartbeat from `t` on (a heartbeat due at or after `t` is not sent).
  void stopHeartbeatAt(TimeNs t) noexcept { heartbeat_stop_at_ = t; }
  /// No TPDOs (the heartbeat continues).
  void setPdoSilent(bool silent) noexcept { pdo_silent_ = silent; }
  /// No frame at all (the drive still receives and runs its state machines).
  void setSilent(bool silent) noexcept { silent_ = silent; }
  /// The next `n` TPDOs are sent one byte short (a corrupt frame to the master).
  void corruptPdos(unsigned n) noexcept { corrupt_left_ = n; }
  /// The master's heartbeats no longer reach the drive (true) or do again (false).
  void setMasterHeartbeatLost(bool lost) noexcept { master_hb_lost_ = lost; }
  /// Answer SDO writes to index:sub with this abort code.
  void abortOnWrite(std::uint16_t index, std::uint8_t sub, std::uint32_t code) noexcept;
  /// Report this mode in the TPDO2 mode display instead of 0x6060.
  void forceModeDisplay(std::int8_t mode) noexcept {
    forced_mode_ = mode;
    force_mode_ = true;
  }

  // ---- observation ----
  std::uint8_t node() const noexcept { return options_.node; }
  mrqp_fw_nmt_state nmt() const noexcept { return nmt_; }
  mrqp_fw_cia402_state state() const noexcept { return state_; }
  /// An object dictionary entry; false if there is none.
  bool od(std::uint16_t index, std::uint8_t sub, std::uint32_t* value) const noexcept;
  /// An object dictionary value, 0 if there is no such entry.
  std::uint32_t odValue(std::uint16_t index, std::uint8_t sub) const noexcept;
  /// Modes of operation (0x6060).
  std::int8_t mode() const noexcept { return static_cast<std::int8_t>(odValue(0x6060, 0)); }
  /// Targets of the last RPDO applied at a SYNC (increments, per mille).
  std::int32_t targetPosition() const noexcept { return target_position_; }
  std::int16_t targetTorque() const noexcept { return target_torque_; }
  std::uint16_t lastControlword() const noexcept { return controlword_; }
  std::uint16_t errorCode() const noexcept { return error_code_; }
  unsigned sdoWrites() const noexcept { return sdo_writes_; }
  unsigned syncs() const noexcept { return syncs_; }
  /// Communication errors (SYNC timeouts) so far; whether one is still active (no SYNC since).
  unsigned commErrors() const noexcept { return comm_errors_; }
  bool commErrorActive() const noexcept { return comm_error_active_; }
  /// Heartbeat consumer timeouts (EMCY 0x8130) and RPDO timeouts (EMCY 0x8250) so far.
  unsigned heartbeatErrors() const noexcept { return heartbeat_errors_; }
  unsigned rpdoTimeouts() const noexcept { return rpdo_timeouts_; }
  const VendorProfile& profile() const noexcept { return options_.profile; }
  bool rpdo1Configured() const noexcept;
  bool tpdo1Configured() const noexcept;
  bool tpdo2Configured() const noexcept;

 private:
  struct Entry {
    std::uint16_t index;
    std::uint8_t sub;
    std::uint8_t size;
    bool writable;
    std::uint32_t value;
  };
  void resetOd(bool communication_only) noexcept;
  bool present(std::uint16_t index) const noexcept;
  TimeNs syncDeadline() const noexcept;
  void commError(TimeNs now) noexcept;
  TimeNs consumerDeadline() const noexcept;
  TimeNs rpdoDeadline() const noexcept;
  bool masterHeartbeat(const mrqp_fw_frame& f) const noexcept;
  void onMasterHeartbeat(TimeNs now) noexcept;
  void heartbeatError(TimeNs now) noexcept;
  void rpdoTimeout(TimeNs now) noexcept;
  void connectionReaction(std::uint16_t code) noexcept;
  void errorBehaviour() noexcept;
  void sendEmcy(std::uint16_t code, TimeNs at) noexcept;
  std::uint16_t otherStatusBits() const noexcept;
  Entry* find(std::uint16_t index, std::uint8_t sub) noexcept;
  const Entry* find(std::uint16_t index, std::uint8_t sub) const noexcept;
  bool objectExists(std::uint16_t index) const noexcept;
  std::uint32_t checkWrite(const Entry& e, std::uint32_t v) const noexcept;
  bool pdoOk(std::uint16_t comm, std::uint16_t map, std::uint32_t cob, mrqp_fw_arm_pdo which) const noexcept;
  void onNmt(const mrqp_fw_frame& f, TimeNs now) noexcept;
  void onSdo(const mrqp_fw_frame& f, TimeNs now) noexcept;
  void onSync(TimeNs now) noexcept;
  void send(mrqp_fw_frame f, TimeNs at, bool pdo) noexcept;

  Host& host_;
  Options options_;
  std::array<Entry, 64> od_{};
  std::size_t od_count_ = 0;
  mrqp_fw_nmt_state nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
  mrqp_fw_cia402_state state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
  TimeNs boot_at_ = kNever;
  TimeNs heartbeat_due_ = kNever;
  TimeNs heartbeat_stop_at_ = kNever;
  std::uint16_t controlword_ = 0;
  std::uint16_t rpdo_controlword_ = 0;
  std::int32_t rpdo_position_ = 0;
  std::int16_t rpdo_torque_ = 0;
  bool rpdo_pending_ = false;
  std::int32_t target_position_ = 0;
  std::int16_t target_torque_ = 0;
  std::uint16_t error_code_ = 0;
  bool pdo_silent_ = false;
  bool silent_ = false;
  unsigned corrupt_left_ = 0;
  bool force_mode_ = false;
  std::int8_t forced_mode_ = 0;
  std::uint16_t abort_index_ = 0;
  std::uint8_t abort_sub_ = 0;
  std::uint32_t abort_code_ = 0;
  unsigned sdo_writes_ = 0;
  unsigned syncs_ = 0;
  TimeNs last_sync_ = kNever;  ///< last SYNC in Operational (kNever: not watching)
  bool comm_error_active_ = false;
  unsigned comm_errors_ = 0;
  TimeNs last_master_hb_ = kNever;  ///< last master heartbeat heard (kNever: not watching)
  bool master_hb_lost_ = false;
  bool hb_error_active_ = false;
  unsigned heartbeat_errors_ = 0;
  TimeNs last_rpdo_ = kNever;  ///< last RPDO1 received in Operational (kNever: not watching)
  unsigned rpdo_timeouts_ = 0;
};

}  // namespace mrqp::emulation
