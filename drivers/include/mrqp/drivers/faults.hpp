// mrqp drivers -- the fault report every driver hands to its caller each cycle.
//
// Plain structs of flags and counters, owned by the driver (capacity fixed at construction) and
// rewritten by every update(): `flags` say what is wrong THIS cycle (a condition that still
// holds, or an event that happened since the previous update); counters are cumulative.
// Nothing here allocates; describeFaults() (for logs, not the cycle) does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "mrqp/drivers/bus.hpp"

namespace mrqp::drivers {

/// Fault flags (bit mask), per device and per bus, OR-ed into FaultReport::flags.
namespace fault {
inline constexpr std::uint32_t kHeartbeatLost = 1u << 0;     ///< no heartbeat within the consumer time
inline constexpr std::uint32_t kFeedbackMissing = 1u << 1;   ///< no feedback for N consecutive cycles
inline constexpr std::uint32_t kEmcy = 1u << 2;              ///< an EMCY with a non-zero code is active
inline constexpr std::uint32_t kDeviceFault = 1u << 3;       ///< the device reports a fault state
inline constexpr std::uint32_t kOutOfRange = 1u << 4;        ///< a feedback value outside its range
inline constexpr std::uint32_t kSetpointRefused = 1u << 5;   ///< a NaN / infinite setpoint was refused
inline constexpr std::uint32_t kSetpointLimited = 1u << 6;   ///< a setpoint was clamped to its limit
inline constexpr std::uint32_t kCorruptFrame = 1u << 7;      ///< a frame failed to decode (dropped)
inline constexpr std::uint32_t kUnknownFrame = 1u << 8;      ///< a frame nobody owns (dropped)
inline constexpr std::uint32_t kBusErrorFrames = 1u << 9;    ///< error frames on the bus
inline constexpr std::uint32_t kBusErrorPassive = 1u << 10;  ///< controller error passive
inline constexpr std::uint32_t kBusOff = 1u << 11;           ///< controller bus-off
inline constexpr std::uint32_t kTxQueueFull = 1u << 12;      ///< a frame was not queued (retried next cycle)
inline constexpr std::uint32_t kRxOverflow = 1u << 13;       ///< received frames were lost
inline constexpr std::uint32_t kStateMismatch = 1u
                                                << 14;  ///< NMT state / mode not as commanded, device reset
inline constexpr std::uint32_t kTimeout = 1u << 15;     ///< boot, SDO, enable or disable took too long
inline constexpr std::uint32_t kBootFailed = 1u << 16;  ///< the configuration of a device failed
inline constexpr std::uint32_t kTornPair = 1u << 17;    ///< two halves of one sample did not match
inline constexpr std::uint32_t kSampleLost = 1u << 18;  ///< a gap in a sequence counter
inline constexpr std::uint32_t kDeviceWarning = 1u << 19;  ///< a device warning (temperature, limit...)
inline constexpr std::uint32_t kRecovering = 1u << 20;     ///< the device is being brought back (recovery)
inline constexpr std::uint32_t kLast = kRecovering;
}  // namespace fault

/// Static name of one flag ("heartbeat lost", ...); "unknown" for other values.
const char* faultFlagName(std::uint32_t flag) noexcept;

/// One device (drive, motor, hand board, sensor).
struct DeviceFaults {
  std::uint32_t flags = 0;              ///< fault:: flags of this cycle
  std::uint32_t missed_cycles = 0;      ///< consecutive cycles without the expected feedback
  std::uint16_t emcy_code = 0;          ///< last EMCY error code (0 = none, or reset)
  std::uint8_t emcy_register = 0;       ///< error register of the last EMCY
  std::uint32_t emcy_count = 0;         ///< EMCY messages received
  std::uint32_t corrupt_frames = 0;     ///< frames of this device that failed to decode (dropped)
  std::uint32_t refused_setpoints = 0;  ///< NaN / infinite setpoints refused (never sent)
  std::uint32_t limited_setpoints = 0;  ///< setpoints clamped to a limit or the wire range
  std::uint32_t out_of_range = 0;       ///< feedback values outside their range
  std::uint32_t torn_pairs = 0;         ///< force/torque pairs rejected as torn
  std::uint32_t lost_samples = 0;       ///< samples missing in the sequence counter
  std::uint32_t tx_queue_full = 0;      ///< frames for this device the bus refused (queue full)
  std::uint32_t sdo_abort_code = 0;     ///< boot: the abort code of the failed SDO write (0 = none)
  std::uint16_t sdo_index = 0;          ///< boot: object of the failed SDO transfer (abort or check)
  std::uint8_t sdo_subindex = 0;
  std::uint8_t node = 0;                 ///< CANopen node id of the device (0: not a CANopen node)
  std::uint8_t nmt_state = 0xFF;         ///< CANopen: last NMT state heard (0xFF: none yet)
  bool sdo_check_failed = false;         ///< boot: a checked object (0x1000, 0x1018) has another value
  std::uint32_t sdo_check_expected = 0;  ///< ... the configured value
  std::uint32_t sdo_check_actual = 0;    ///< ... the value read
  std::uint32_t sdo_check_mask = 0;      ///< ... the bits compared
  std::uint32_t tolerated_aborts = 0;    ///< boot: PDO-disabling writes answered "object does not exist"
  std::uint32_t recoveries = 0;          ///< times the device was brought back (recovery completed)
};

/// One bus, as seen by a driver.
struct BusFaults {
  std::uint32_t flags = 0;  ///< fault:: bus flags of this cycle
  BusState state = BusState::ErrorActive;
  std::uint16_t tec = 0;
  std::uint16_t rec = 0;
  std::uint32_t error_events = 0;     ///< error frames this cycle
  std::uint32_t error_flags = 0;      ///< bus_error:: flags of this cycle's error frames
  std::uint32_t unknown_frames = 0;   ///< frames nobody claimed this cycle
  std::uint32_t rejected_frames = 0;  ///< frames claimed but malformed this cycle
  std::uint32_t tx_queue_full = 0;    ///< sends refused (queue full) this cycle
  std::uint32_t rx_overflow = 0;      ///< frames lost to receive overflow this cycle
  std::uint64_t error_events_total = 0;
  std::uint64_t unknown_total = 0;
  std::uint64_t rejected_total = 0;
  std::uint64_t tx_queue_full_total = 0;
  std::uint64_t rx_overflow_total = 0;
};

/// What update() returns: views into arrays the driver owns, valid until the next update().
struct FaultReport {
  std::uint64_t cycle = 0;  ///< number of update() calls so far
  std::uint32_t flags = 0;  ///< OR of every device and bus flag of this cycle
  const DeviceFaults* devices = nullptr;
  std::size_t device_count = 0;
  const BusFaults* buses = nullptr;
  std::size_t bus_count = 0;

  bool ok() const noexcept { return flags == 0u; }
  bool has(std::uint32_t flag) const noexcept { return (flags & flag) != 0u; }
};

/// Human-readable summary of the flags raised in a report, one line per device/bus with flags
/// (for logs; allocates). Empty when the report is ok().
std::string describeFaults(const FaultReport& report, const char* what = "device");

/// One device's flags with what they mean (allocates): the node, the EMCY code and its CiA 301 /
/// CiA 402 meaning, the NMT state of a state mismatch, an SDO abort with its code, meaning, object
/// and node, a failed identity / device type check with the values expected and read.
std::string describeDeviceFaults(const DeviceFaults& device);

/// Comma-separated names of the flags in a mask (allocates).
std::string faultFlagsStr(std::uint32_t flags);

}  // namespace mrqp::drivers
