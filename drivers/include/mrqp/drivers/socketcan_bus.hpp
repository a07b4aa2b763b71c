// mrqp drivers -- Linux SocketCAN back end (AF_CAN, SOCK_RAW, CAN_RAW).
//
// open() (setup, may allocate) creates a non-blocking raw CAN socket bound to one interface and
// configures it: acceptance filters (CAN_RAW_FILTER), error frames (CAN_RAW_ERR_FILTER, all
// classes), optional CAN FD (CAN_RAW_FD_FRAMES, after checking the interface MTU), kernel receive
// timestamps (SO_TIMESTAMPNS, read with recvmsg and converted from CLOCK_REALTIME to
// CLOCK_MONOTONIC) and the receive-queue drop counter (SO_RXQ_OVFL).
//
// send()/receive() are real-time safe: one write()/recvmsg() system call, a fixed control
// buffer, no allocation. ENOBUFS / EAGAIN on send mean "transmit queue full": the frame is not
// sent, SendResult::QueueFull is returned, the caller retries next cycle, status().tx_queue_full
// counts it. Error frames update status() (state, counters) and are returned as error events.
//
// A kernel without CAN support (no AF_CAN) makes open() fail with a message starting
// "AF_CAN not supported by this kernel".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrqp/drivers/bus.hpp"

namespace mrqp::drivers {

/// Receive filter: a frame passes when (frame_id & mask) == (id & mask).
struct CanIdFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
};

struct SocketCanConfig {
  std::string interface = "can0";
  bool fd = false;                   ///< enable CAN FD frames (the interface MTU must be CANFD_MTU)
  std::vector<CanIdFilter> filters;  ///< empty: receive every frame
  bool error_frames = true;          ///< receive error frames (all error classes)
  bool timestamps = true;            ///< kernel receive timestamps (SO_TIMESTAMPNS)
  bool receive_own = false;          ///< CAN_RAW_RECV_OWN_MSGS (frames this socket sent)
  int send_buffer_bytes = 0;         ///< SO_SNDBUF; 0 keeps the default
};

class SocketCanBus final : public Bus {
 public:
  SocketCanBus() = default;
  ~SocketCanBus() override;

  /// Opens and configures the socket. On failure returns false and, if `error` is not null,
  /// a message naming the failing step and the system error.
  bool open(const SocketCanConfig& config, std::string* error);
  void close() noexcept;
  bool isOpen() const noexcept { return fd_ >= 0; }
  int nativeHandle() const noexcept { return fd_; }

  SendResult send(const mrqp_fw_frame& frame) noexcept override;
  ReceiveResult receive(RxFrame& out) noexcept override;
  BusStatus status() const noexcept override { return status_; }
  bool fdEnabled() const noexcept override { return fd_frames_; }
  const char* name() const noexcept override { return name_; }
  bool echoesOwn() const noexcept override { return receive_own_; }

  /// errno of the last failed system call in send()/receive() (0 if none).
  int lastErrno() const noexcept { return last_errno_; }

 private:
  void onErrorFrame(const std::uint8_t* data, std::uint32_t can_id, RxFrame& out) noexcept;

  int fd_ = -1;
  bool fd_frames_ = false;
  bool receive_own_ = false;
  int last_errno_ = 0;
  std::uint32_t last_drop_count_ = 0;
  BusStatus status_{};
  char name_[24] = "socketcan";
  alignas(8) unsigned char control_[128] = {};  ///< recvmsg control buffer (timestamp, drops)
};

}  // namespace mrqp::drivers
