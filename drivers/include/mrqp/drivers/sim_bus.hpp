// mrqp drivers -- the in-process CAN bus: a deterministic model of the physical layer for tests.
//
// A SimBus is the wire; each SimNode attached to it is one CAN controller and implements Bus.
// Time is simulated and only moves when the test calls advance()/advanceTo(). The model:
//
//  - bit rates: nominal (arbitration) rate, and for CAN FD the data-phase rate used by frames
//    with the bit-rate switch (BRS) flag;
//  - frame duration: firmware_if/bus_timing.h bit counts (with worst-case stuffing by default,
//    or without stuffing) at those rates, intermission included;
//  - arbitration: when the bus becomes idle, every node with a frame ready starts in the same
//    slot and the lowest identifier wins (for equal identifiers a classic frame beats an FD frame,
//    r0 being dominant where FD sends FDF recessive); losers retry when the bus is idle again;
//    two nodes sending the same identifier with different content destroy each other's frame
//    (bit error for both), identical frames are sent together;
//  - acknowledgement: a frame that no other connected, non-bus-off node acknowledges (listen-only
//    nodes and, for FD frames, classic-only nodes do not) ends in an ACK error;
//  - fault confinement (ISO 11898-1): TEC +8 per transmit error, -1 per successful transmission;
//    REC +1 per receive error, -1 per successful reception (a REC above 127 is set to 119);
//    warning >= 96, error passive >= 128, bus-off when TEC > 255. Exception 1 of the standard
//    applies: an error-passive transmitter's ACK error does not raise its TEC, so a node alone on
//    the bus ends error passive at TEC 128 (after 16 attempts), never bus-off. A bus-off node is
//    disconnected (its queue is flushed, sends are refused) and, when auto_recover is set,
//    returns to error active with both counters 0 after 128 occurrences of 11 consecutive
//    recessive bits (idle bus time, and the 11 recessive bits that end every frame);
//  - an error-passive transmitter (passive after the counters of the attempt are updated) waits
//    8 more bit times ("suspend transmission") after each of its transmissions; frames destroyed
//    by an error are retransmitted automatically (unless one_shot), after a 6-bit error flag,
//    8-bit delimiter and 3-bit intermission;
//  - each node's transmit queue is ordered by ready time (FIFO for frames ready at the same
//    time), like a SocketCAN queue; sendAt() lets a fake device schedule a frame later.
//
// Frames are delivered to a node's receive queue (or its SimListener) at the end of the frame,
// timestamped with that time. A SimListener is how tests emulate device firmware: it is called
// from inside advance() at the simulated time of the event (reception, end of its own
// transmission, its timer) and may send frames or set its timer; it must not call advance().
// Construction and addNode() allocate; everything else is real-time safe (no allocation).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mrqp/drivers/bus.hpp"
#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/bus_timing.h"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

struct SimBusConfig {
  std::uint32_t nominal_bps = 1000000;  ///< arbitration (and classic) bit rate, > 0
  std::uint32_t data_bps = 0;           ///< CAN FD data-phase rate; 0 = a classic bus (FD refused)
  bool worst_case_stuffing = true;      ///< frame durations with the maximum stuff-bit count
  std::size_t max_nodes = 32;
};

struct SimNodeConfig {
  const char* name = "node";   ///< static string, for messages
  bool fd = false;             ///< CAN FD capable controller (on a FD bus)
  std::size_t tx_queue = 64;   ///< frames
  std::size_t rx_queue = 256;  ///< frames and error events
  bool acknowledge = true;     ///< false: listen-only, never acknowledges
  bool error_events = true;    ///< deliver error events to receive() (SocketCAN's error filter)
  bool auto_recover = true;    ///< leave bus-off after 128 x 11 recessive bits
  bool one_shot = false;       ///< drop a frame after a failed attempt instead of retrying
  bool echo_own = false;  ///< receive own frames once delivered (RxFrame::own), like CAN_RAW_RECV_OWN_MSGS
};

/// What happened to one transmission attempt on the wire.
enum class WireOutcome : std::uint8_t { Delivered = 0, NoAck, BitError, Collision };

const char* wireOutcomeStr(WireOutcome outcome) noexcept;

struct WireEvent {
  TimeNs start = 0;
  TimeNs end = 0;        ///< end of the attempt (intermission included)
  std::size_t node = 0;  ///< transmitting node index (the lowest on a collision)
  mrqp_fw_frame frame{};
  WireOutcome outcome = WireOutcome::Delivered;
  mrqp_fw_frame_bits bits{};  ///< bits of this attempt at the nominal and data rates
};

/// Observer of every transmission attempt (a "bus analyser" for tests).
class SimTap {
 public:
  virtual void onWire(const WireEvent& event) noexcept = 0;

 protected:
  ~SimTap() = default;
};

class SimNode;

/// Emulated firmware attached to a node: receives instead of the node's receive queue.
class SimListener {
 public:
  /// A data frame (kind Frame) or an error event (kind ErrorEvent) reached the node.
  virtual void onReceive(SimNode& node, ReceiveResult kind, const RxFrame& rx) noexcept = 0;
  /// One of the node's frames was transmitted successfully; `end` is the end of the frame.
  virtual void onTransmitted(SimNode& node, const mrqp_fw_frame& frame, TimeNs end) noexcept;
  /// The node's timer (SimNode::setTimer) expired at `now`.
  virtual void onTimer(SimNode& node, TimeNs now) noexcept;

 protected:
  ~SimListener() = default;
};

struct SimBusStats {
  std::uint64_t attempts = 0;
  std::uint64_t delivered = 0;
  std::uint64_t no_ack = 0;
  std::uint64_t bit_errors = 0;
  std::uint64_t collisions = 0;
  TimeNs busy_ns = 0;  ///< total time the wire carried a frame or an error
};

class SimBus;

/// One CAN controller on a SimBus.
class SimNode final : public Bus {
 public:
  SendResult send(const mrqp_fw_frame& frame) noexcept override;
  ReceiveResult receive(RxFrame& out) noexcept override;
  BusStatus status() const noexcept override;
  bool fdEnabled() const noexcept override;
  const char* name() const noexcept override;
  bool echoesOwn() const noexcept override { return config_.echo_own; }

  /// Queues a frame that becomes ready for arbitration at `ready` (>= now).
  SendResult sendAt(const mrqp_fw_frame& frame, TimeNs ready) noexcept;
  /// Drops every frame waiting in the transmit queue (a controller reset), not counted as failed.
  void cancelPending() noexcept;
  /// Frames waiting in the transmit queue.
  std::size_t txPending() const noexcept { return tx_count_; }
  /// Receive-queue items waiting.
  std::size_t rxPending() const noexcept { return rx_count_; }
  std::size_t index() const noexcept { return index_; }
  SimBus& bus() noexcept { return *bus_; }
  const SimNodeConfig& config() const noexcept { return config_; }

  /// One-shot timer for the listener (a firmware timer): onTimer() is called at `at` (replaces
  /// a pending timer). Timers fire even while the bus is busy.
  void setTimer(TimeNs at) noexcept { timer_at_ = at; }
  void cancelTimer() noexcept { timer_at_ = kNoTimer; }
  /// Routes received frames and error events to `listener` instead of the receive queue.
  void setListener(SimListener* listener) noexcept { listener_ = listener; }
  /// Power / wiring: a disconnected node neither transmits, receives nor acknowledges; its
  /// queues are flushed. Reconnecting starts error active with both counters 0.
  void setConnected(bool connected) noexcept;
  bool connected() const noexcept { return connected_; }
  /// The next `count` transmission attempts of this node suffer a bit error (noise).
  void injectTxErrors(std::uint32_t count) noexcept { inject_errors_ += count; }

  ~SimNode() override;

 private:
  friend class SimBus;
  struct TxEntry {
    mrqp_fw_frame frame;
    TimeNs ready;
  };
  struct RxItem {
    RxFrame rx;
    bool error;
  };

  SimNode(SimBus& bus, std::size_t index, const SimNodeConfig& config);
  bool frameValid(const mrqp_fw_frame& frame) const noexcept;
  const TxEntry& txHead() const noexcept { return tx_[tx_head_]; }
  void txPop() noexcept;
  void txFlush() noexcept;
  void deliver(ReceiveResult kind, const RxFrame& rx) noexcept;
  void emitError(std::uint32_t flags, TimeNs when) noexcept;
  /// Sets counters, derives the state and emits one event with `flags` + state-change flags.
  void setCounters(std::uint32_t tec, std::uint32_t rec, std::uint32_t flags, TimeNs when) noexcept;

  static constexpr TimeNs kNoTimer = INT64_MAX;
  SimBus* bus_;
  std::size_t index_;
  TimeNs timer_at_ = kNoTimer;
  SimNodeConfig config_;
  SimListener* listener_ = nullptr;
  std::vector<TxEntry> tx_;
  std::size_t tx_head_ = 0;
  std::size_t tx_count_ = 0;
  std::vector<RxItem> rx_;
  std::size_t rx_head_ = 0;
  std::size_t rx_count_ = 0;
  bool connected_ = true;
  BusState state_ = BusState::ErrorActive;
  std::uint32_t tec_ = 0;
  std::uint32_t rec_ = 0;
  TimeNs suspend_until_ = 0;
  std::uint32_t inject_errors_ = 0;
  std::uint32_t recovery_occurrences_ = 0;  ///< 11-recessive-bit sequences seen while bus-off
  TimeNs recovery_recessive_ns_ = 0;        ///< recessive time of the current partial sequence
  BusStatus counters_{};
};

/// The wire and the simulated clock.
class SimBus {
 public:
  explicit SimBus(const SimBusConfig& config = SimBusConfig{});
  SimBus(const SimBus&) = delete;
  SimBus& operator=(const SimBus&) = delete;
  ~SimBus();

  /// Attaches a new node (setup: allocates). Returns nullptr once max_nodes are attached.
  SimNode* addNode(const SimNodeConfig& config);
  std::size_t nodeCount() const noexcept { return nodes_.size(); }
  SimNode& node(std::size_t i) noexcept { return *nodes_[i]; }

  TimeNs now() const noexcept { return now_; }
  /// Runs the bus until now() + dt / until t (no-op if t < now()).
  void advance(TimeNs dt) noexcept { advanceTo(now_ + dt); }
  void advanceTo(TimeNs t) noexcept;

  /// Bits of a successful transmission of `frame` (with this bus's stuffing model).
  mrqp_fw_frame_bits frameBits(const mrqp_fw_frame& frame) const noexcept;
  /// Duration in ns of `bits` at this bus's rates.
  TimeNs bitsTime(mrqp_fw_frame_bits bits) const noexcept;
  /// Duration of a successful transmission of `frame`.
  TimeNs frameTime(const mrqp_fw_frame& frame) const noexcept { return bitsTime(frameBits(frame)); }
  /// One nominal bit time in ns (rounded up).
  TimeNs bitTime() const noexcept;

  void setTap(SimTap* tap) noexcept { tap_ = tap; }
  const SimBusStats& stats() const noexcept { return stats_; }
  const SimBusConfig& config() const noexcept { return config_; }
  bool busy() const noexcept { return busy_; }

 private:
  friend class SimNode;
  static constexpr TimeNs kNever = INT64_MAX;

  TimeNs eligibleTime(const SimNode& n) const noexcept;
  TimeNs nextTimer() const noexcept;
  void fireTimers(TimeNs t) noexcept;
  TimeNs nextTxStart() const noexcept;
  TimeNs nextRecovery() const noexcept;
  void accountIdle(TimeNs t) noexcept;
  void recoverDue(TimeNs t) noexcept;
  void startFrame(TimeNs t) noexcept;
  void finishFrame() noexcept;
  bool isReceiver(const SimNode& n) const noexcept;

  SimBusConfig config_;
  std::vector<std::unique_ptr<SimNode>> nodes_;
  TimeNs now_ = 0;
  TimeNs bus_free_ = 0;           ///< end of the last attempt
  TimeNs idle_mark_ = 0;          ///< idle time accounted for bus-off recovery up to here
  TimeNs occurrence_ns_ = 11000;  ///< 11 nominal bit times
  bool busy_ = false;
  WireEvent current_{};
  std::vector<std::size_t> participants_;  ///< transmitters of the current attempt
  std::size_t participant_count_ = 0;
  SimTap* tap_ = nullptr;
  SimBusStats stats_{};
};

}  // namespace mrqp::drivers
