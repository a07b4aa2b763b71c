// A fake CANopen CiA 402 drive for the driver tests, built from the firmware_if drive-side state
// machines (NMT, CiA 402 drive_next/drive_event) and SDO frames, attached to a SimNode as its
// firmware. It keeps a small object dictionary with CiA 301 default values and rules (PDO
// mapping only while the PDO is disabled and its entry count is 0, sizes and access checked),
// produces its heartbeat from 0x1017, applies RPDO1 and sends TPDO1/TPDO2 on SYNC only when they
// are configured exactly as the mrqp contract maps them. Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/firmware_if/firmware_if.h>

#include <array>
#include <cstdint>

namespace drvtest {

using mrqp::drivers::RxFrame;
using mrqp::drivers::SimNode;
using mrqp::drivers::TimeNs;

struct FakeDriveOptions {
  std::uint8_t node = 1;
  TimeNs boot_delay = 2000000;      ///< reset -> boot-up message (2 ms)
  TimeNs response_delay = 20000;    ///< SDO answer / TPDO after SYNC (20 us)
  std::int32_t initial_position = 0;
  mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
};

class FakeCia402Drive final : public mrqp::drivers::SimListener {
 public:
  FakeCia402Drive(SimNode& node, const FakeDriveOptions& options);

  void on_receive(SimNode& node, mrqp::drivers::ReceiveResult kind, const RxFrame& rx) noexcept override;
  void on_transmitted(SimNode& node, const mrqp_fw_frame& frame, TimeNs end) noexcept override;
  void on_timer(SimNode& node, TimeNs now) noexcept override;

  // ---- test controls ----
  /// Power off (disconnects the node: no frames, no ACK) / on (boots again).
  void power(bool on) noexcept;
  /// A fault: EMCY with `code`, then Fault reaction active -> Fault at the next SYNC.
  void inject_fault(std::uint16_t code, std::uint8_t error_register) noexcept;
  /// Stop sending TPDOs (heartbeat continues).
  void set_pdo_silent(bool silent) noexcept { pdo_silent_ = silent; }
  /// Answer SDO writes to index:sub with an abort.
  void abort_on_write(std::uint16_t index, std::uint8_t sub, std::uint32_t code) noexcept;
  /// Report this mode in the mode display instead of 0x6060.
  void force_mode_display(std::int8_t mode) noexcept { forced_mode_ = mode; force_mode_ = true; }

  // ---- observation ----
  mrqp_fw_nmt_state nmt() const noexcept { return nmt_; }
  mrqp_fw_cia402_state state() const noexcept { return state_; }
  bool od(std::uint16_t index, std::uint8_t sub, std::uint32_t* value) const noexcept;
  std::int32_t target_position() const noexcept { return target_position_; }
  std::int16_t target_torque() const noexcept { return target_torque_; }
  std::int32_t position() const noexcept { return position_; }
  std::uint16_t last_controlword() const noexcept { return controlword_; }
  unsigned sdo_writes() const noexcept { return sdo_writes_; }
  unsigned syncs() const noexcept { return syncs_; }
  bool tpdo1_configured() const noexcept;
  bool tpdo2_configured() const noexcept;
  bool rpdo1_configured() const noexcept;

 private:
  struct Entry {
    std::uint16_t index;
    std::uint8_t sub;
    std::uint8_t size;
    bool writable;
    std::uint32_t value;
  };
  void reset_od(bool communication_only) noexcept;
  Entry* find(std::uint16_t index, std::uint8_t sub) noexcept;
  const Entry* find(std::uint16_t index, std::uint8_t sub) const noexcept;
  bool object_exists(std::uint16_t index) const noexcept;
  std::uint32_t value(std::uint16_t index, std::uint8_t sub) const noexcept;
  std::uint32_t check_write(const Entry& e, std::uint32_t v) const noexcept;
  bool pdo_ok(std::uint16_t comm, std::uint16_t map, std::uint32_t cob, mrqp_fw_arm_pdo which) const noexcept;
  void on_nmt(const mrqp_fw_frame& f, TimeNs now) noexcept;
  void on_sdo(const mrqp_fw_frame& f, TimeNs now) noexcept;
  void on_sync(TimeNs now) noexcept;
  void send_later(const mrqp_fw_frame& f, TimeNs at) noexcept;

  SimNode& node_;
  FakeDriveOptions opt_;
  std::array<Entry, 48> od_{};
  std::size_t od_count_ = 0;
  mrqp_fw_nmt_state nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
  mrqp_fw_cia402_state state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
  bool booting_ = false;
  TimeNs heartbeat_due_ = 0;
  std::uint16_t controlword_ = 0;
  std::uint16_t rpdo_controlword_ = 0;
  std::int32_t rpdo_position_ = 0;
  std::int16_t rpdo_torque_ = 0;
  bool rpdo_pending_ = false;
  std::int32_t target_position_ = 0;
  std::int16_t target_torque_ = 0;
  std::int32_t position_ = 0;
  std::int32_t velocity_ = 0;
  std::int16_t torque_ = 0;
  std::uint16_t error_code_ = 0;
  bool pdo_silent_ = false;
  bool powered_ = true;
  bool force_mode_ = false;
  std::int8_t forced_mode_ = 0;
  std::uint16_t abort_index_ = 0;
  std::uint8_t abort_sub_ = 0;
  std::uint32_t abort_code_ = 0;
  unsigned sdo_writes_ = 0;
  unsigned syncs_ = 0;
};

}  // namespace drvtest
