// mrqp drivers -- arm drives: a CANopen (CiA 301) master for CiA 402 drives in CSP or CST.
//
// One ArmDriver runs any number of drives spread over one or more buses (BusRouter). It is a
// non-blocking state machine stepped by the control cycle:
//
//   start()      Resetting    NMT reset node (or reset communication) per drive; wait for every
//                             boot-up message (0x700 + node, 0x00) that answers it: sent after
//                             the reset was on the bus (NmtBoot: the reset's TX echo on a bus
//                             with echoes, else its send time). With reset None: NMT enter
//                             pre-operational instead, no wait.
//                Configuring  expedited SDO writes per drive, one in flight per drive (all drives
//                             in parallel): producer heartbeat 0x1017, consumer heartbeat 0x1016:1
//                             (when the master sends a heartbeat), communication cycle 0x1006,
//                             RPDO1/TPDO1/TPDO2 mapping (disable, transmission type 1, map, enable;
//                             RPDO1's event timer 0x1400:05 when rpdo_timeout_ms is set),
//                             TPDO3/TPDO4 disabled, modes of operation 0x6060 (CSP 8 / CST 10).
//                             Optionally first reads device type 0x1000 and identity 0x1018:1..3
//                             and checks them against the drive's configuration. TPDO COB-IDs are
//                             written with bit 30 = 1 (no RTR) unless tpdo_rtr_allowed; a write that
//                             disables a PDO is satisfied by abort 0x06020000 (the drive has fewer
//                             PDOs: CiA 301 leaves their number to the device).
//                Starting     NMT start per drive.
//                Running      every cycle, per bus: one RPDO1 per drive (controlword, target
//                             position, target torque) and then one SYNC. TPDO1 (statusword,
//                             position, torque) and TPDO2 (velocity, error code, mode display)
//                             are decoded when they arrive.
//   requestEnable() / requestDisable() / requestQuickStop(): the controlword of each drive
//   follows mrqp_fw_cia402_master_controlword (firmware_if), one transition per cycle, until the
//   target state is reported by the statusword. A drive that falls into Fault is flagged and
//   left there (target Switch on disabled) until the next requestEnable(), which resets it.
//
// Recovery (see docs/drivers.md, "Bringing up a vendor's drive"): a drive that leaves
// Operational (its heartbeat reports pre-operational or stopped), reboots (boot-up message) or
// falls into Fault while enabled is flagged (kStateMismatch with the NMT state, kEmcy with the
// code) and needs recovery: reconfigure if it rebooted, NMT start, CiA 402 enable (fault reset).
// requestRecovery(now) starts it for every drive that needs it; with ArmConfig::recovery =
// Automatic the driver starts it by itself. Neither happens while setSafeState(true) is in force:
// the loop sets it while its safe state holds, and the driver then recovers nothing.
//
// Safe exit: requestSafeExit(now) stops every drive (quick stop, or disable voltage, as
// ArmConfig::exit_stop), waits until each reports it (or exit_timeout), then sends NMT enter
// pre-operational or stop (exit_nmt) to each drive; safeExitDone() then holds (phase Stopped,
// no cyclic traffic). Works from any phase (a failed boot goes straight to the NMT command). A
// drive that is not Operational (PDOs stopped) and was last seen with its power stage on gets the
// controlword 0x0000 (disable voltage) by an SDO write to 0x6040 before its NMT command.
//
// SYNC jitter: the interval between successive SYNCs of each bus, timed on the TX echo where the
// bus returns the master's own frames (else at transmit()), against the cycle period: syncStats().
//
// The control cycle calls, in order: BusRouter::poll(now) for each bus, update(now) (faults and
// state machine), setPosition()/setTorque(), transmit(now).
// The CANopen master's protocol objects are units of their own (drivers/canopen, one per file):
// NmtBoot (reset and boot-up wait, NMT start) and HeartbeatConsumer per drive, SdoWriteSequence
// (the configuration writes) per drive, SyncProducer per bus, HeartbeatProducer (the master's
// heartbeat); ArmDriver sequences them and adds the CiA 402 part. Everything after create() is
// real-time safe: no allocation, no lock, no exception, no stdio; failures are return values and
// fault flags. Until a drive is enabled and given a setpoint, its RPDO holds its measured position
// (raw increments) with zero torque.
//
// As a JointDevice (device.hpp) joint i is drive i: a CSP drive is JointMode::Position
// (setJoint: target position, and the command's torque as the RPDO's torque feed-forward; the
// RPDO has no velocity), a CST drive JointMode::Torque (setJoint: target torque).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/canopen/heartbeat_consumer.hpp"
#include "mrqp/drivers/canopen/heartbeat_producer.hpp"
#include "mrqp/drivers/canopen/nmt_boot.hpp"
#include "mrqp/drivers/canopen/sdo_write_sequence.hpp"
#include "mrqp/drivers/canopen/sync_jitter.hpp"
#include "mrqp/drivers/canopen/sync_producer.hpp"
#include "mrqp/drivers/device.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/router_attachment.hpp"
#include "mrqp/drivers/setpoint.hpp"
#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/arm_scale.h"
#include "mrqp/firmware_if/cia402.h"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

struct ArmDriveConfig {
  std::size_t bus = 0;    ///< index into the routers given to ArmDriver::create
  std::uint8_t node = 1;  ///< CANopen node id 1..127
  mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  std::int8_t mode = MRQP_FW_MODE_CSP;                              ///< MRQP_FW_MODE_CSP or MRQP_FW_MODE_CST
  double position_min = -std::numeric_limits<double>::infinity();   ///< rad
  double position_max = std::numeric_limits<double>::infinity();    ///< rad
  double torque_limit = std::numeric_limits<double>::infinity();    ///< N m, absolute
  double velocity_limit = std::numeric_limits<double>::infinity();  ///< rad/s, feedback check only
  /// Checked at boot (read before the configuration) when non-zero: device type 0x1000 (bits of
  /// device_type_mask; default the profile number, 402 = 0x0192, in the low 16 bits), vendor id
  /// 0x1018:1, product code 0x1018:2, revision 0x1018:3. A mismatch fails the boot.
  std::uint32_t device_type = 0;
  std::uint32_t device_type_mask = 0x0000FFFFu;
  std::uint32_t vendor_id = 0;
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
};

/// Who starts a recovery (see ArmDriver): the caller (requestRecovery) or the driver itself.
enum class RecoveryPolicy : std::uint8_t { Manual = 0, Automatic };
/// How requestSafeExit() stops the power stage.
enum class ExitStop : std::uint8_t { QuickStop = 0, DisableVoltage };
/// The NMT state requestSafeExit() leaves the drives in.
enum class ExitNmt : std::uint8_t { PreOperational = 0, Stopped, Unchanged };

struct ArmConfig {
  std::vector<ArmDriveConfig> drives;
  TimeNs cycle_period = milliseconds(1);   ///< control cycle (written to 0x1006)
  bool tpdo2 = true;                       ///< map and enable TPDO2 (velocity, error code, mode)
  bool produce_sync = true;                ///< send one SYNC per bus and cycle
  std::uint8_t sync_counter_overflow = 0;  ///< 0: SYNC without counter; 2..240: counter
  NmtReset reset = NmtReset::Node;
  std::uint16_t producer_heartbeat_ms = 100;     ///< written to 0x1017; 0: no heartbeat monitoring
  TimeNs heartbeat_timeout = milliseconds(250);  ///< consumer time of the master
  std::uint8_t master_node = 0;                  ///< != 0: send a master heartbeat as this node id
  std::uint16_t master_heartbeat_ms = 100;
  std::uint16_t drive_consumer_ms = 300;  ///< written to 0x1016:1 when master_node != 0
  bool write_cycle_period = true;         ///< write 0x1006 (microseconds)
  /// The value written to 0x1006 in microseconds; 0: the cycle period. A drive that enforces a SYNC
  /// timeout takes a multiple of it (1.5 x is common): a loop with SYNC gaps beyond that needs a
  /// larger value, or the drive leaves Operational (see syncStats()).
  std::uint32_t comm_cycle_period_us = 0;
  /// The SYNC timeout factor of the drives, for syncStats().over_timeout (gaps a drive would take
  /// for a lost SYNC).
  double sync_timeout_factor = 1.5;
  /// != 0: written to 0x1400:05, RPDO1's event timer, which CiA 301 drives take as the RPDO's
  /// deadline (ms): a drive that watches it reacts when no RPDO1 arrives for longer. 0: not written.
  std::uint16_t rpdo_timeout_ms = 0;
  /// TPDO COB-IDs with bit 30 = 0 ("RTR allowed"); false (default): bit 30 = 1, as many drives require.
  bool tpdo_rtr_allowed = false;
  /// Abort 0x06020000 answers a write that disables a PDO the drive does not have (TPDO3/4, TPDO2
  /// without tpdo2): the PDO is absent, as good as disabled. false: any abort fails the boot.
  bool tolerate_absent_pdos = true;
  RecoveryPolicy recovery = RecoveryPolicy::Manual;
  TimeNs recovery_retry = seconds(1);  ///< Automatic: at most one recovery start per drive per this
  ExitStop exit_stop = ExitStop::QuickStop;
  ExitNmt exit_nmt = ExitNmt::PreOperational;
  TimeNs exit_timeout = milliseconds(500);    ///< requestSafeExit: longest wait for the stop
  std::uint32_t feedback_missing_cycles = 3;  ///< consecutive cycles without TPDO1 -> fault
  TimeNs boot_timeout = seconds(5);           ///< reset -> all boot-up messages
  TimeNs sdo_timeout = milliseconds(100);     ///< per SDO request
  TimeNs enable_timeout = seconds(1);         ///< request -> target state reached
};

enum class ArmPhase : std::uint8_t {
  Idle = 0,
  Resetting,
  Configuring,
  Starting,
  Running,
  Failed,
  Stopping,
  Stopped
};
const char* armPhaseStr(ArmPhase phase) noexcept;

/// What the driver knows about one drive, updated by the received frames.
struct ArmDriveState {
  double position = 0.0;  ///< rad
  double velocity = 0.0;  ///< rad/s (TPDO2)
  double torque = 0.0;    ///< N m
  std::int32_t position_inc = 0;
  std::int32_t velocity_inc = 0;
  std::int16_t torque_permille = 0;
  std::uint16_t statusword = 0;
  mrqp_fw_cia402_state state = MRQP_FW_CIA402_UNKNOWN;
  std::int8_t mode_display = 0;
  std::uint16_t error_code = 0;   ///< 0x603F from TPDO2
  std::uint8_t nmt_state = 0xFF;  ///< last heartbeat state (0xFF: none yet)
  std::uint16_t controlword = 0;  ///< last controlword sent
  bool valid = false;             ///< a TPDO1 has been received
  bool fresh = false;             ///< a TPDO1 arrived since the previous update()
  TimeNs timestamp = 0;           ///< reception time of the last TPDO1
};

class ArmDriver final : public JointDevice, public FrameHandler {
 public:
  /// Validates the configuration and registers with the routers (setup; allocates). Returns
  /// nullptr and a message naming the offending drive/field if the configuration is invalid.
  static std::unique_ptr<ArmDriver> create(const std::vector<BusRouter*>& buses, const ArmConfig& config,
                                           std::string* error);
  ArmDriver(const ArmDriver&) = delete;
  ArmDriver& operator=(const ArmDriver&) = delete;

  const char* kind() const noexcept override { return "arm"; }
  /// Starts (or restarts) the boot sequence.
  void start(TimeNs now) noexcept override;
  /// Running, every drive reports Operation enabled, and none needs or is in a recovery.
  bool ready() const noexcept override;
  /// Moves every drive to Operation enabled (resetting faults).
  void requestEnable(TimeNs now) noexcept override;
  /// Moves every drive to Switch on disabled.
  void requestDisable(TimeNs now) noexcept override;
  /// Quick stop: Operation enabled -> Quick stop active (others to Switch on disabled).
  void requestQuickStop(TimeNs now) noexcept override;

  /// After polling the buses: timeouts, state machines, fault flags of this cycle.
  const FaultReport& update(TimeNs now) noexcept override;
  /// Setpoints for the next transmit(): target position (CSP) / target torque (CST).
  SetpointResult setPosition(std::size_t drive, double rad) noexcept;
  SetpointResult setTorque(std::size_t drive, double nm) noexcept;
  /// Sends this cycle's frames. Returns the number of frames queued.
  std::size_t transmit(TimeNs now) noexcept override;

  // JointDevice: joint i is drive i.
  std::size_t jointCount() const noexcept override { return drives_.size(); }
  JointMode jointMode(std::size_t joint) const noexcept override;
  SetpointResult setJoint(std::size_t joint, const JointCommand& command) noexcept override;
  JointFeedback joint(std::size_t joint) const noexcept override;

  Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;
  /// The TX echo of the master's NMT commands (see NmtBoot).
  void onOwnFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;

  ArmPhase phase() const noexcept { return phase_; }
  /// Every drive reports Operation enabled.
  bool allEnabled() const noexcept;
  /// Every drive reports Switch on disabled (or Not ready to switch on).
  bool allDisabled() const noexcept;
  std::size_t driveCount() const noexcept { return drives_.size(); }
  const ArmDriveState& drive(std::size_t i) const noexcept { return drives_[i].state; }
  const FaultReport& faults() const noexcept override { return routers_.report(); }
  /// Adds this driver's cyclic traffic on bus `bus` (index as given to create) to a budget.
  void declareTraffic(std::size_t bus, BusBudget& budget) const override;

  /// Starts the recovery of every drive that needs it (see the top of this file). Returns the
  /// number of drives whose recovery started; 0 while the safe state is in force or not Running.
  std::size_t requestRecovery(TimeNs now) noexcept;
  /// The loop's safe state: while true no recovery starts (manual or automatic), and recoveries
  /// under way stop before enabling the drive.
  void setSafeState(bool in_force) noexcept { safe_state_ = in_force; }
  bool safeState() const noexcept { return safe_state_; }
  /// The drive needs a recovery (left Operational, rebooted, or fell into Fault while enabled).
  bool needsRecovery(std::size_t drive) const noexcept;
  /// A recovery of the drive is under way.
  bool recovering(std::size_t drive) const noexcept;

  /// Stops every drive and leaves it in the configured NMT state (see the top of this file).
  void requestSafeExit(TimeNs now) noexcept;
  bool safeExitDone() const noexcept { return phase_ == ArmPhase::Stopped; }

  /// SYNC intervals and jitter of bus `bus` (index as given to create).
  const SyncStats& syncStats(std::size_t bus) const noexcept { return buses_[bus].jitter.stats(); }

 private:
  struct Drive {
    ArmDriveConfig cfg;
    ArmDriveState state;
    DeviceFaults faults;
    std::uint32_t events = 0;  ///< flags raised since the previous update
    NmtBoot nmt;               ///< reset, boot-up wait, NMT start
    SdoWriteSequence sdo;      ///< the boot configuration
    HeartbeatConsumer heartbeat;
    mrqp_fw_frame pending{};  ///< one-shot frame waiting for the queue (NMT, SDO)
    bool has_pending = false;
    mrqp_fw_cia402_state target = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
    TimeNs target_since = 0;
    bool target_timed_out = false;
    double sp_position = 0.0;
    double sp_torque = 0.0;
    bool sp_position_valid = false;
    bool sp_torque_valid = false;
    bool got_tpdo1 = false;
    bool tpdo2_seen = false;
    std::uint32_t sticky = 0;  ///< flags that hold until the next start() (boot failure)
    mrqp_fw_cia402_state prev_state = MRQP_FW_CIA402_UNKNOWN;
    Claim last_claim = Claim::Accepted;
    // Recovery.
    enum class Recovery : std::uint8_t { None = 0, Configuring, Starting };
    Recovery recovery = Recovery::None;
    bool rebooted = false;  ///< a boot-up while running: the configuration is lost
    bool recovery_failed = false;
    TimeNs recovery_since = 0;
    TimeNs recovery_attempt = 0;
    bool attempted = false;
    // Safe exit: 0 nothing queued, 1 SDO controlword write queued (NMT next), 2 NMT queued, 3 done.
    std::uint8_t exit_step = 0;
  };
  struct BusSlot {
    std::array<std::int16_t, 128> node_to_drive{};
    bool cyclic_sent = false;  ///< cyclic traffic (RPDOs, SYNC) has started
    SyncProducer sync;
    SyncJitter jitter;
    bool has_drives = false;
  };

  ArmDriver() = default;
  std::vector<SdoWrite> buildWrites(const ArmDriveConfig& drive) const;
  bool send(std::size_t slot, Drive* d, const mrqp_fw_frame& f) noexcept;
  void setPending(Drive& d, const mrqp_fw_frame& f) noexcept;
  void failBoot(Drive& d, std::uint32_t flags) noexcept;
  /// After one step of a drive's SDO write sequence (boot or recovery): a failed step keeps the
  /// frame it could not send, records the abort and its object, fails the boot; true then.
  bool failedSdoStep(Drive& d, SdoWriteSequence::Step step, const mrqp_fw_frame& out) noexcept;
  void setTarget(mrqp_fw_cia402_state target, TimeNs now) noexcept;
  Claim onSdo(Drive& d, const mrqp_fw_frame& f) noexcept;
  void decodeTpdo1(Drive& d, const mrqp_fw_frame& f, TimeNs t) noexcept;
  void decodeTpdo2(Drive& d, const mrqp_fw_frame& f) noexcept;
  void startRecovery(Drive& d, TimeNs now) noexcept;
  void stepRecovery(Drive& d, TimeNs now) noexcept;
  void transmitRecovery(Drive& d, std::size_t* count, TimeNs now) noexcept;
  void stepSafeExit(TimeNs now) noexcept;
  void queueExitNmt(Drive& d) noexcept;
  std::size_t transmitCyclic(TimeNs now) noexcept;

  ArmConfig config_;
  std::vector<Drive> drives_;
  std::vector<BusSlot> buses_;
  ArmPhase phase_ = ArmPhase::Idle;
  TimeNs phase_since_ = 0;
  mrqp_fw_cia402_state wanted_ = MRQP_FW_CIA402_SWITCH_ON_DISABLED;  ///< the caller's last request
  bool safe_state_ = false;
  TimeNs exit_since_ = 0;
  bool exit_nmt_stage_ = false;  ///< safe exit: the power stage is stopped, the NMT commands go out
  HeartbeatProducer master_heartbeat_;
  RouterAttachment routers_;
};

}  // namespace mrqp::drivers
