// mrqp drivers -- SocketCAN back end: the real-time part (send, receive). See socketcan_bus.hpp.
#include "mrqp/drivers/socketcan_bus.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace mrqp::drivers {

namespace {

TimeNs timespecNs(const timespec& ts) noexcept {
  return static_cast<TimeNs>(ts.tv_sec) * 1000000000 + static_cast<TimeNs>(ts.tv_nsec);
}

// Offset CLOCK_MONOTONIC - CLOCK_REALTIME now (two vDSO reads).
TimeNs realtimeToMonotonicOffset() noexcept {
  timespec mono{};
  timespec real{};
  clock_gettime(CLOCK_MONOTONIC, &mono);
  clock_gettime(CLOCK_REALTIME, &real);
  return timespecNs(mono) - timespecNs(real);
}

}  // namespace

SendResult SocketCanBus::send(const mrqp_fw_frame& frame) noexcept {
  if (fd_ < 0) {
    ++status_.tx_failed;
    return SendResult::Down;
  }
  if (status_.state == BusState::BusOff) {
    ++status_.tx_failed;
    return SendResult::BusOff;
  }
  const bool fd_frame = (frame.flags & MRQP_FW_FRAME_FD) != 0u;
  if ((frame.flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR)) != 0u || frame.id > CAN_SFF_MASK ||
      (fd_frame && (!fd_frames_ || mrqp_fw_fd_len_valid(frame.len) == 0)) ||
      (!fd_frame && frame.len > CAN_MAX_DLEN)) {
    ++status_.tx_failed;
    return SendResult::Invalid;
  }
  ssize_t n = 0;
  std::size_t size = 0;
  if (fd_frame) {
    canfd_frame f{};
    f.can_id = frame.id;
    f.len = frame.len;
    f.flags = (frame.flags & MRQP_FW_FRAME_BRS) != 0u ? CANFD_BRS : 0;
    std::memcpy(f.data, frame.data, frame.len);
    size = sizeof(f);
    n = ::write(fd_, &f, size);
  } else {
    can_frame f{};
    f.can_id = frame.id;
    f.len = frame.len;
    std::memcpy(f.data, frame.data, frame.len);
    size = sizeof(f);
    n = ::write(fd_, &f, size);
  }
  if (n == static_cast<ssize_t>(size)) {
    ++status_.tx_frames;
    return SendResult::Ok;
  }
  last_errno_ = n < 0 ? errno : EIO;
  if (last_errno_ == ENOBUFS || last_errno_ == EAGAIN) {
    ++status_.tx_queue_full;  // qdisc / socket buffer full: retried by the caller next cycle
    return SendResult::QueueFull;
  }
  ++status_.tx_failed;
  if (last_errno_ == ENETDOWN || last_errno_ == ENXIO || last_errno_ == ENODEV || last_errno_ == EBADF) {
    return SendResult::Down;
  }
  return SendResult::Failed;
}

void SocketCanBus::onErrorFrame(const std::uint8_t* data, std::uint32_t can_id, RxFrame& out) noexcept {
  std::uint32_t flags = 0;
  const std::uint32_t cls = can_id & CAN_ERR_MASK;
  if ((cls & CAN_ERR_TX_TIMEOUT) != 0u) {
    flags |= bus_error::kTxTimeout;
  }
  if ((cls & CAN_ERR_ACK) != 0u) {
    flags |= bus_error::kAck | bus_error::kTransmitting;
  }
  if ((cls & CAN_ERR_TRX) != 0u) {
    flags |= bus_error::kTransceiver;
  }
  if ((cls & CAN_ERR_PROT) != 0u) {
    const std::uint8_t type = data[2];
    const std::uint8_t where = data[3];
    if ((type & (CAN_ERR_PROT_BIT | CAN_ERR_PROT_BIT0 | CAN_ERR_PROT_BIT1)) != 0u) {
      flags |= bus_error::kBit;
    }
    if ((type & CAN_ERR_PROT_FORM) != 0u) {
      flags |= bus_error::kForm;
    }
    if ((type & CAN_ERR_PROT_STUFF) != 0u) {
      flags |= bus_error::kStuff;
    }
    if ((type & CAN_ERR_PROT_TX) != 0u) {
      flags |= bus_error::kTransmitting;
    }
    if (where == CAN_ERR_PROT_LOC_CRC_SEQ || where == CAN_ERR_PROT_LOC_CRC_DEL) {
      flags |= bus_error::kCrc;
    }
    if ((flags & (bus_error::kBit | bus_error::kForm | bus_error::kStuff | bus_error::kCrc)) == 0u) {
      flags |= bus_error::kProtocol;
    }
  }
  if ((cls & CAN_ERR_BUSERROR) != 0u) {
    flags |= bus_error::kProtocol;
  }
  if ((cls & CAN_ERR_CRTL) != 0u) {
    const std::uint8_t c = data[1];
    if ((c & CAN_ERR_CRTL_RX_OVERFLOW) != 0u) {
      flags |= bus_error::kRxOverflow;
    }
    if ((c & CAN_ERR_CRTL_TX_OVERFLOW) != 0u) {
      flags |= bus_error::kTxOverflow;
    }
    if ((c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0u) {
      flags |= bus_error::kWarning;
    }
    if ((c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0u) {
      flags |= bus_error::kPassive;
    }
    if ((c & CAN_ERR_CRTL_ACTIVE) != 0u) {
      flags |= bus_error::kActive;
    }
  }
  if ((cls & CAN_ERR_BUSOFF) != 0u) {
    flags |= bus_error::kBusOff;
  }
  if ((cls & CAN_ERR_RESTARTED) != 0u) {
    flags |= bus_error::kRestarted;
  }
  // State: the most severe condition reported wins; a restart or "active" clears it.
  if ((flags & bus_error::kBusOff) != 0u) {
    status_.state = BusState::BusOff;
  } else if ((flags & (bus_error::kRestarted | bus_error::kActive)) != 0u) {
    status_.state = BusState::ErrorActive;
  } else if ((flags & bus_error::kPassive) != 0u) {
    status_.state = BusState::ErrorPassive;
  } else if ((flags & bus_error::kWarning) != 0u && status_.state == BusState::ErrorActive) {
    status_.state = BusState::ErrorWarning;
  }
  out.error.flags = flags;
  out.error.counters_valid = false;
#ifdef CAN_ERR_CNT
  if ((cls & CAN_ERR_CNT) != 0u) {
    status_.tec = data[6];
    status_.rec = data[7];
    out.error.counters_valid = true;
  }
#endif
  if ((flags & bus_error::kRestarted) != 0u && !out.error.counters_valid) {
    status_.tec = 0;
    status_.rec = 0;
  }
  out.error.tec = status_.tec;
  out.error.rec = status_.rec;
  ++status_.error_events;
}

ReceiveResult SocketCanBus::receive(RxFrame& out) noexcept {
  if (fd_ < 0) {
    return ReceiveResult::Empty;
  }
  canfd_frame f{};
  iovec iov{};
  iov.iov_base = &f;
  iov.iov_len = sizeof(f);
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control_;
  msg.msg_controllen = sizeof(control_);
  const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
      return ReceiveResult::Empty;
    }
    last_errno_ = errno;
    ++status_.rx_failed;
    return ReceiveResult::Failed;
  }
  out = RxFrame{};
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level != SOL_SOCKET) {
      continue;
    }
    if (c->cmsg_type == SCM_TIMESTAMPNS && c->cmsg_len >= CMSG_LEN(sizeof(timespec))) {
      timespec ts{};
      std::memcpy(&ts, CMSG_DATA(c), sizeof(ts));
      out.timestamp = timespecNs(ts) + realtimeToMonotonicOffset();
      out.has_timestamp = true;
    } else if (c->cmsg_type == SO_RXQ_OVFL && c->cmsg_len >= CMSG_LEN(sizeof(std::uint32_t))) {
      std::uint32_t drops = 0;
      std::memcpy(&drops, CMSG_DATA(c), sizeof(drops));
      status_.rx_overflow += static_cast<std::uint32_t>(drops - last_drop_count_);
      last_drop_count_ = drops;
    }
  }
  if (!out.has_timestamp) {
    out.timestamp = monotonicNow();
  }
  out.own = (msg.msg_flags & MSG_CONFIRM) != 0;  // CAN_RAW_RECV_OWN_MSGS: this socket's own frame
  const bool is_fd = n == static_cast<ssize_t>(CANFD_MTU);
  if (!is_fd && n != static_cast<ssize_t>(CAN_MTU)) {
    last_errno_ = EIO;
    ++status_.rx_failed;
    return ReceiveResult::Failed;
  }
  if ((f.can_id & CAN_ERR_FLAG) != 0u) {
    onErrorFrame(f.data, f.can_id, out);
    return ReceiveResult::ErrorEvent;
  }
  mrqp_fw_frame& fr = out.frame;
  fr.flags = 0;
  if ((f.can_id & CAN_EFF_FLAG) != 0u) {
    fr.flags |= MRQP_FW_FRAME_EXT;
    fr.id = f.can_id & CAN_EFF_MASK;
  } else {
    fr.id = f.can_id & CAN_SFF_MASK;
  }
  if ((f.can_id & CAN_RTR_FLAG) != 0u) {
    fr.flags |= MRQP_FW_FRAME_RTR;
  }
  std::uint8_t len = f.len;
  if (is_fd) {
    fr.flags |= MRQP_FW_FRAME_FD;
    if ((f.flags & CANFD_BRS) != 0u) {
      fr.flags |= MRQP_FW_FRAME_BRS;
    }
    if (len > CANFD_MAX_DLEN) {
      len = CANFD_MAX_DLEN;
    }
  } else if (len > CAN_MAX_DLEN) {
    len = CAN_MAX_DLEN;
  }
  fr.len = len;
  std::memcpy(fr.data, f.data, len);
  ++status_.rx_frames;
  return ReceiveResult::Frame;
}

}  // namespace mrqp::drivers
