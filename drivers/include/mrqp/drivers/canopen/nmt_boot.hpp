// mrqp drivers -- CANopen master, NMT: one node's boot (the reset command and the wait for its
// boot-up message) and the NMT state the master commanded.
//
// begin() writes the command that starts a boot (reset node 0x81, reset communication 0x82, or
// enter pre-operational 0x80 without a reset and without a wait); the caller sends it and says
// when (sent()). The node has booted when a boot-up message (heartbeat state 0x00) answers that
// command, i.e. was sent by the node after the command was on the bus. A boot-up from before (the
// node's power-up, sent just before the reset went out) is not an answer: the node is rebooting
// and will send another. The proof of order:
//  - on a bus that returns the master's own frames (Bus::echoesOwn(): CAN_RAW_RECV_OWN_MSGS,
//    SimNodeConfig::echo_own), the command's TX echo (onOwnCommand()) is received in wire order
//    with the node's frames: only a boot-up received after the echo counts;
//  - without echoes, only a boot-up received at or after the time the command was handed to the
//    bus counts (one received earlier certainly came first; one received later but sent while the
//    command waited for the bus is not caught: use a bus with echoes).
// startRemote() writes NMT start (0x01) and remembers when the node was told to be operational.
// process(now) reports a boot that has not completed within the boot timeout.
// Everything but the frames' transport; real-time safe, no allocation.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

enum class NmtReset : std::uint8_t {
  Node = 0,       ///< NMT reset node (0x81): application reset, wait for boot-up
  Communication,  ///< NMT reset communication (0x82), wait for boot-up
  None            ///< NMT enter pre-operational (0x80), no reset, no wait
};

class NmtBoot {
 public:
  void init(std::uint8_t node, NmtReset reset, TimeNs boot_timeout) noexcept;

  /// Starts a boot at `now`: the NMT frame to send in `out`.
  void begin(TimeNs now, mrqp_fw_frame* out) noexcept;
  /// NMT start remote node: the frame in `out`; the node is expected operational from `now`.
  void startRemote(TimeNs now, mrqp_fw_frame* out) noexcept;
  /// The boot command was handed to the bus at `now`.
  void sent(TimeNs now) noexcept;
  /// Whether the bus returns the master's own frames (then a boot-up only counts after the echo).
  void setEcho(bool echo) noexcept { echo_ = echo; }
  /// The master's own NMT frame `f` came back from the bus (TX echo). True if it was this node's
  /// boot command (or a broadcast one) while the boot is awaited.
  bool onOwnCommand(const mrqp_fw_frame& f) noexcept;
  /// A boot-up message of the node received at `t`. True if it answers the boot command (the
  /// node is booted); false if it came before the command was on the bus, or is not awaited.
  bool onBootUp(TimeNs t) noexcept;
  /// True when the boot has not completed within the boot timeout of begin().
  bool process(TimeNs now) const noexcept;

  bool booted() const noexcept { return booted_; }
  bool waiting() const noexcept { return !booted_ && begun_; }
  /// When the node's current NMT state was commanded (begin() or startRemote()).
  TimeNs commanded() const noexcept { return commanded_; }
  std::uint8_t node() const noexcept { return node_; }

 private:
  std::uint8_t node_ = 1;
  NmtReset reset_ = NmtReset::Node;
  TimeNs boot_timeout_ = 0;
  TimeNs commanded_ = 0;
  bool begun_ = false;
  bool booted_ = false;
  bool echo_ = false;
  bool sent_ = false;  ///< the boot command was handed to the bus
  TimeNs sent_at_ = 0;
  bool echoed_ = false;  ///< ... and came back from it
};

}  // namespace mrqp::drivers
