// mrqp drivers -- SocketCAN back end: opening and configuring the socket (setup, not real time).
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "mrqp/drivers/socketcan_bus.hpp"

namespace mrqp::drivers {

namespace {

std::string errnoText(int e) { return std::string(std::strerror(e)); }

bool fail(std::string* error, const std::string& message) {
  if (error != nullptr) {
    *error = message;
  }
  return false;
}

}  // namespace

SocketCanBus::~SocketCanBus() { close(); }

void SocketCanBus::close() noexcept {
  if (fd_ >= 0) {
    ::close(fd_);
  }
  fd_ = -1;
  fd_frames_ = false;
  receive_own_ = false;
}

bool SocketCanBus::open(const SocketCanConfig& config, std::string* error) {
  close();
  status_ = BusStatus{};
  last_errno_ = 0;
  last_drop_count_ = 0;
  const std::string& ifname = config.interface;
  if (ifname.empty() || ifname.size() >= IFNAMSIZ) {
    return fail(error, "SocketCAN: invalid interface name '" + ifname + "' (1 to " +
                           std::to_string(IFNAMSIZ - 1) + " characters)");
  }

  const int s = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (s < 0) {
    const int e = errno;
    if (e == EAFNOSUPPORT || e == EPROTONOSUPPORT || e == ESOCKTNOSUPPORT) {
      return fail(error,
                  "AF_CAN not supported by this kernel (socket(AF_CAN, SOCK_RAW, CAN_RAW): " + errnoText(e) +
                      "): SocketCAN needs the can and can_raw kernel modules; use the in-process "
                      "bus (SimBus) here, or run on a kernel with CAN support (e.g. the HIL VM "
                      "with vcan, see docs/drivers.md)");
    }
    return fail(error, "SocketCAN: socket(AF_CAN, SOCK_RAW, CAN_RAW) failed: " + errnoText(e));
  }
  auto give_up = [&](const std::string& what, int e) {
    ::close(s);
    return fail(error, "SocketCAN " + ifname + ": " + what + ": " + errnoText(e));
  };

  ifreq ifr{};
  std::memcpy(ifr.ifr_name, ifname.c_str(), ifname.size() + 1);
  if (::ioctl(s, SIOCGIFINDEX, &ifr) < 0) {
    return give_up("no such CAN interface (SIOCGIFINDEX)", errno);
  }
  const int ifindex = ifr.ifr_ifindex;

  if (config.fd) {
    ifreq mtu{};
    std::memcpy(mtu.ifr_name, ifname.c_str(), ifname.size() + 1);
    if (::ioctl(s, SIOCGIFMTU, &mtu) < 0) {
      return give_up("cannot read the interface MTU (SIOCGIFMTU)", errno);
    }
    if (mtu.ifr_mtu < static_cast<int>(CANFD_MTU)) {
      ::close(s);
      return fail(error, "SocketCAN " + ifname + ": CAN FD requested but the interface MTU is " +
                             std::to_string(mtu.ifr_mtu) + " (" + std::to_string(CANFD_MTU) +
                             " needed: 'ip link set " + ifname +
                             " mtu 72' or configure the "
                             "controller with 'fd on')");
    }
    const int on = 1;
    if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof(on)) < 0) {
      return give_up("setsockopt(CAN_RAW_FD_FRAMES)", errno);
    }
  }

  if (!config.filters.empty()) {
    std::vector<can_filter> filters;
    filters.reserve(config.filters.size());
    for (const CanIdFilter& f : config.filters) {
      filters.push_back(can_filter{f.id, f.mask});
    }
    if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                     static_cast<socklen_t>(filters.size() * sizeof(can_filter))) < 0) {
      return give_up("setsockopt(CAN_RAW_FILTER)", errno);
    }
  }

  const can_err_mask_t err_mask = config.error_frames ? CAN_ERR_MASK : 0u;
  if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) < 0) {
    return give_up("setsockopt(CAN_RAW_ERR_FILTER)", errno);
  }
  const int own = config.receive_own ? 1 : 0;
  if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own)) < 0) {
    return give_up("setsockopt(CAN_RAW_RECV_OWN_MSGS)", errno);
  }
  if (config.timestamps) {
    const int on = 1;
    if (::setsockopt(s, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on)) < 0) {
      return give_up("setsockopt(SO_TIMESTAMPNS)", errno);
    }
  }
  {
    const int on = 1;
    if (::setsockopt(s, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on)) < 0) {
      return give_up("setsockopt(SO_RXQ_OVFL)", errno);
    }
  }
  if (config.send_buffer_bytes > 0) {
    if (::setsockopt(s, SOL_SOCKET, SO_SNDBUF, &config.send_buffer_bytes, sizeof(config.send_buffer_bytes)) <
        0) {
      return give_up("setsockopt(SO_SNDBUF)", errno);
    }
  }

  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifindex;
  if (::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) < 0) {
    return give_up("bind()", errno);
  }

  fd_ = s;
  fd_frames_ = config.fd;
  receive_own_ = config.receive_own;
  const std::size_t n = std::min(ifname.size(), sizeof(name_) - 1);
  std::memcpy(name_, ifname.c_str(), n);
  name_[n] = '\0';
  return true;
}

}  // namespace mrqp::drivers
