// mrqp drivers -- hand controller boards on CAN FD (firmware_if/hand_fd_frame.h).
//
// Every cycle each board gets ceil(joints / 11) command frames (identifier 0x120 + board, BRS),
// all with the same sequence number (incremented every cycle) and the requested mode: DISABLED
// until requestEnable(), then the configured mode (POSITION or TORQUE), DISABLED again after
// requestDisable(). Commands are sent in every mode so the board's command timeout never fires
// and its feedback (0x140 + board, one frame per 11 joints) keeps coming. The driver checks each
// feedback frame (CRC, version, layout: the firmware_if unpack), the feedback counter (a gap is
// lost frames), the sequence echo (lagging more than max_seq_lag cycles: commands not applied),
// the status bits (fault, over-temperature, command timeout, CRC error seen, limit) and, once
// enabled, that the board reports the requested mode. Until a joint is given a setpoint after
// enabling, it is commanded to its measured position with zero velocity and torque.
//
// Cycle: BusRouter::poll, update(now), setJoint(), transmit(now). Real-time safe after create().
//
// As a JointDevice (device.hpp) the joints of all boards are numbered in configuration order
// (board 0's joints, then board 1's, ...). The mode is that of enabled_mode: POSITION ->
// JointMode::Position (position, velocity and feed-forward torque; the board's own gains, the
// command's stiffness and damping are not on the wire), TORQUE -> JointMode::Torque.
// requestQuickStop() puts every board into HOLD (the board holds its position; setpoints ignored).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/device.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/router_attachment.hpp"
#include "mrqp/drivers/setpoint.hpp"
#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/hand_fd_frame.h"

namespace mrqp::drivers {

struct HandBoardConfig {
  std::size_t bus = 0;       ///< index into the routers given to create(); the bus must be CAN FD
  std::uint8_t board = 0;    ///< 0..15
  std::uint8_t joints = 20;  ///< 1..32
  mrqp_fw_hand_scale scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
};

struct FdHandConfig {
  std::vector<HandBoardConfig> boards;
  std::uint8_t enabled_mode = MRQP_FW_HAND_MODE_POSITION;  ///< POSITION or TORQUE
  std::uint32_t feedback_missing_cycles = 3;
  std::uint16_t max_seq_lag = 2;  ///< cycles the echoed sequence may lag behind
  TimeNs enable_timeout = milliseconds(100);
};

struct HandJointState {
  float position = 0.0f;  ///< rad
  float velocity = 0.0f;  ///< rad/s
  float torque = 0.0f;    ///< N m
};

struct HandBoardState {
  std::uint8_t mode = 0xFF;    ///< mode reported by the board (0xFF: none yet)
  std::uint8_t status = 0;     ///< MRQP_FW_HAND_STATUS_* of the last feedback
  std::uint16_t seq = 0;       ///< sequence of the last command sent
  std::uint16_t seq_echo = 0;  ///< last sequence echoed by the board
  std::uint8_t counter = 0;    ///< last feedback counter
  bool valid = false;          ///< complete feedback received at least once
  bool fresh = false;          ///< every feedback frame of this cycle arrived
  bool enabled = false;        ///< the board confirmed the requested (non-disabled) mode
  TimeNs timestamp = 0;        ///< reception time of the last feedback frame
};

class FdHandDriver final : public JointDevice, public FrameHandler {
 public:
  static std::unique_ptr<FdHandDriver> create(const std::vector<BusRouter*>& buses,
                                              const FdHandConfig& config, std::string* error);
  FdHandDriver(const FdHandDriver&) = delete;
  FdHandDriver& operator=(const FdHandDriver&) = delete;

  const char* kind() const noexcept override { return "fd_hand"; }
  /// Nothing to boot: boards are commanded (DISABLED) from the first transmit().
  void start(TimeNs) noexcept override {}
  bool ready() const noexcept override { return allEnabled(); }
  void requestEnable(TimeNs now) noexcept override;
  void requestDisable(TimeNs now) noexcept override;
  /// Every board to HOLD.
  void requestQuickStop(TimeNs now) noexcept override;

  const FaultReport& update(TimeNs now) noexcept override;
  /// Setpoint of joint `joint` of board `board` (index in the configuration).
  SetpointResult setJoint(std::size_t board, std::size_t joint, float position, float velocity,
                          float torque) noexcept;
  std::size_t transmit(TimeNs now) noexcept override;

  // JointDevice: the joints of all boards in configuration order.
  std::size_t jointCount() const noexcept override { return joint_count_; }
  JointMode jointMode(std::size_t joint) const noexcept override;
  SetpointResult setJoint(std::size_t joint, const JointCommand& command) noexcept override;
  JointFeedback joint(std::size_t joint) const noexcept override;

  Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;

  std::size_t boardCount() const noexcept { return boards_.size(); }
  const HandBoardState& board(std::size_t i) const noexcept { return boards_[i].state; }
  const HandJointState& joint(std::size_t board, std::size_t j) const noexcept {
    return boards_[board].joints[j];
  }
  bool allEnabled() const noexcept;
  const FaultReport& faults() const noexcept override { return routers_.report(); }
  void declareTraffic(std::size_t bus, BusBudget& budget) const override;

 private:
  struct Board {
    HandBoardConfig cfg;
    HandBoardState state;
    DeviceFaults faults;
    std::uint32_t events = 0;
    std::array<HandJointState, MRQP_FW_HAND_MAX_JOINTS> joints{};
    std::array<HandJointState, MRQP_FW_HAND_MAX_JOINTS> sp{};
    std::uint32_t sp_valid = 0;     ///< bit per joint
    std::uint32_t chunks = 0;       ///< frames per cycle and direction
    std::uint32_t chunks_seen = 0;  ///< bit per feedback frame this cycle
    bool counter_valid = false;
    bool sent = false;  ///< commands went out at the previous transmit
    std::uint8_t mode_requested = MRQP_FW_HAND_MODE_DISABLED;
    TimeNs mode_since = 0;
  };
  struct BusSlot {
    std::array<std::int16_t, 16> board_to_index{};
  };
  FdHandDriver() = default;
  /// Board and joint of a flat joint index; false when out of range.
  bool locate(std::size_t flat, std::size_t* board, std::size_t* joint) const noexcept;

  FdHandConfig config_;
  std::size_t joint_count_ = 0;
  std::vector<Board> boards_;
  std::vector<BusSlot> buses_;
  RouterAttachment routers_;
};

}  // namespace mrqp::drivers
