// mrqp drivers -- the CAN bus interface seen by the drivers.
//
// A Bus sends and receives mrqp_fw_frame (the firmware_if wire contract's frame) and reports
// the controller's error state. Two implementations: SocketCanBus (Linux raw CAN sockets) and
// SimNode (a node on the in-process SimBus, for deterministic tests).
//
// Real-time contract: send(), receive() and status() never allocate, lock, throw or print; they
// report every failure by return value. A full transmit queue (ENOBUFS on SocketCAN) is
// SendResult::QueueFull: the frame is not sent, the caller retries next cycle, the bus counts it.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

/// Fault-confinement state of the CAN controller (ISO 11898-1): error active (both counters
/// < 96), warning (a counter >= 96), error passive (a counter >= 128), bus-off (TEC > 255).
enum class BusState : std::uint8_t { ErrorActive = 0, ErrorWarning, ErrorPassive, BusOff };

const char* busStateStr(BusState state) noexcept;

/// Flags of a bus error event (SocketCAN error frame, or a SimBus error notification).
namespace bus_error {
inline constexpr std::uint32_t kAck = 1u << 0;            ///< transmitted frame not acknowledged
inline constexpr std::uint32_t kBit = 1u << 1;            ///< bit error (sent level not read back)
inline constexpr std::uint32_t kStuff = 1u << 2;          ///< stuff error
inline constexpr std::uint32_t kForm = 1u << 3;           ///< form error
inline constexpr std::uint32_t kCrc = 1u << 4;            ///< CAN CRC error
inline constexpr std::uint32_t kProtocol = 1u << 5;       ///< other / unspecified protocol error
inline constexpr std::uint32_t kTxTimeout = 1u << 6;      ///< the device driver gave up a transmission
inline constexpr std::uint32_t kRxOverflow = 1u << 7;     ///< controller receive buffer overflow
inline constexpr std::uint32_t kTxOverflow = 1u << 8;     ///< controller transmit buffer overflow
inline constexpr std::uint32_t kWarning = 1u << 9;        ///< a counter reached the warning level (96)
inline constexpr std::uint32_t kPassive = 1u << 10;       ///< entered error passive (a counter >= 128)
inline constexpr std::uint32_t kBusOff = 1u << 11;        ///< entered bus-off (TEC > 255)
inline constexpr std::uint32_t kRestarted = 1u << 12;     ///< left bus-off (recovery / restart)
inline constexpr std::uint32_t kActive = 1u << 13;        ///< back to error active
inline constexpr std::uint32_t kTransceiver = 1u << 14;   ///< transceiver (wiring) problem
inline constexpr std::uint32_t kTransmitting = 1u << 15;  ///< the error happened while this node transmitted
}  // namespace bus_error

/// A bus error event; tec/rec are the counters after the event (when known).
struct BusErrorEvent {
  std::uint32_t flags = 0;  ///< bus_error::k*
  std::uint16_t tec = 0;
  std::uint16_t rec = 0;
  bool counters_valid = false;
};

/// One received item: a data frame or an error event.
struct RxFrame {
  mrqp_fw_frame frame{};  ///< valid for ReceiveResult::Frame
  BusErrorEvent error{};  ///< valid for ReceiveResult::ErrorEvent
  TimeNs timestamp = 0;   ///< reception time on the caller's clock (see has_timestamp)
  bool has_timestamp = false;
  bool own = false;  ///< a frame this bus itself sent, returned once it was on the wire (TX echo)
};

enum class SendResult : std::uint8_t {
  Ok = 0,
  QueueFull,  ///< transmit queue full (ENOBUFS / EAGAIN): not sent, retry next cycle, counted
  BusOff,     ///< the controller is bus-off: not sent
  Invalid,    ///< not a frame this bus can send (length, FD on a classic bus, extended id)
  Down,       ///< interface down / socket closed
  Failed      ///< another system error (counted)
};

enum class ReceiveResult : std::uint8_t {
  Empty = 0,   ///< nothing pending
  Frame,       ///< a data frame in RxFrame::frame
  ErrorEvent,  ///< an error event in RxFrame::error (also reflected in status())
  Failed       ///< a system error (counted)
};

/// Controller state and cumulative counters.
struct BusStatus {
  BusState state = BusState::ErrorActive;
  std::uint16_t tec = 0;            ///< transmit error counter (last known)
  std::uint16_t rec = 0;            ///< receive error counter (last known)
  std::uint64_t tx_frames = 0;      ///< frames accepted for transmission
  std::uint64_t rx_frames = 0;      ///< data frames received
  std::uint64_t error_events = 0;   ///< error frames / events received
  std::uint64_t tx_queue_full = 0;  ///< sends refused because the queue was full (ENOBUFS)
  std::uint64_t tx_failed = 0;      ///< sends refused for another reason (bus-off, invalid, errno)
  std::uint64_t rx_overflow = 0;    ///< frames lost because the receive queue overflowed
  std::uint64_t rx_failed = 0;      ///< receive system errors
};

/// Abstract CAN bus (one controller / socket).
class Bus {
 public:
  Bus() = default;
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;
  virtual ~Bus();

  /// Queues one frame for transmission. Never blocks.
  virtual SendResult send(const mrqp_fw_frame& frame) noexcept = 0;
  /// Takes one received frame or error event. Never blocks.
  virtual ReceiveResult receive(RxFrame& out) noexcept = 0;
  /// Controller state and counters.
  virtual BusStatus status() const noexcept = 0;
  /// True if CAN FD frames can be sent and received.
  virtual bool fdEnabled() const noexcept = 0;
  /// A static name for messages (interface or node name).
  virtual const char* name() const noexcept = 0;
  /// True if receive() also returns this bus's own frames once they were on the wire (RxFrame::own:
  /// CAN_RAW_RECV_OWN_MSGS on SocketCAN, SimNodeConfig::echo_own on SimBus), in wire order with
  /// the frames of the other nodes.
  virtual bool echoesOwn() const noexcept { return false; }
};

}  // namespace mrqp::drivers
