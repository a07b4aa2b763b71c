// SocketCAN back end on a virtual CAN interface (vcan0, CAN FD MTU). Before main, when
// socket(AF_CAN) fails (this kernel has no CAN support) or vcan0 does not exist, the program
// prints why and exits with 77, which CTest reports as "skipped". Run it in the HIL VM, or on a
// host with
//   modprobe vcan && ip link add dev vcan0 type vcan && ip link set vcan0 mtu 72 up
#include <catch2/catch.hpp>

#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/socketcan_bus.hpp>

#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace mrqp::drivers;

namespace {

const char* kInterface = "vcan0";

bool receiveOne(SocketCanBus& bus, RxFrame& rx, ReceiveResult want = ReceiveResult::Frame) {
  for (int i = 0; i < 200; ++i) {
    const ReceiveResult r = bus.receive(rx);
    if (r == want) {
      return true;
    }
    if (r == ReceiveResult::Empty) {
      ::usleep(1000);
    }
  }
  return false;
}

mrqp_fw_frame classic(std::uint32_t id, std::uint8_t len) {
  mrqp_fw_frame f{};
  f.id = id;
  f.len = len;
  for (unsigned i = 0; i < len; ++i) {
    f.data[i] = static_cast<std::uint8_t>(i + 1);
  }
  return f;
}

}  // namespace

TEST_CASE("drivers: vcan: classic frames between two sockets, with kernel timestamps",
          "[drivers][socketcan][vcan]") {
  SocketCanBus a;
  SocketCanBus b;
  SocketCanConfig cfg;
  cfg.interface = kInterface;
  std::string err;
  REQUIRE(a.open(cfg, &err));
  REQUIRE(b.open(cfg, &err));
  const TimeNs before = monotonicNow();
  REQUIRE(a.send(classic(0x123, 8)) == SendResult::Ok);
  RxFrame rx;
  REQUIRE(receiveOne(b, rx));
  const TimeNs after = monotonicNow();
  CHECK(rx.frame.id == 0x123u);
  CHECK(rx.frame.len == 8u);
  CHECK(rx.frame.flags == 0u);
  CHECK(rx.frame.data[7] == 8u);
  CHECK(rx.has_timestamp);
  // The kernel stamp, converted to CLOCK_MONOTONIC, lies within the send/receive window.
  CHECK(rx.timestamp >= before - milliseconds(5));
  CHECK(rx.timestamp <= after + milliseconds(5));
  CHECK(b.status().rx_frames == 1u);
  CHECK(a.status().tx_frames == 1u);
  // Not received by the sender (CAN_RAW_RECV_OWN_MSGS off).
  RxFrame own;
  CHECK(a.receive(own) == ReceiveResult::Empty);
}

TEST_CASE("drivers: vcan: ID filters", "[drivers][socketcan][vcan]") {
  SocketCanBus tx;
  SocketCanBus rx;
  SocketCanConfig cfg;
  cfg.interface = kInterface;
  std::string err;
  REQUIRE(tx.open(cfg, &err));
  cfg.filters = {{0x180, 0x780}};  // 0x180..0x1FF only
  REQUIRE(rx.open(cfg, &err));
  REQUIRE(tx.send(classic(0x201, 1)) == SendResult::Ok);
  REQUIRE(tx.send(classic(0x181, 2)) == SendResult::Ok);
  RxFrame f;
  REQUIRE(receiveOne(rx, f));
  CHECK(f.frame.id == 0x181u);
  ::usleep(5000);
  CHECK(rx.receive(f) == ReceiveResult::Empty);
}

TEST_CASE("drivers: vcan: CAN FD frames when enabled", "[drivers][socketcan][vcan]") {
  SocketCanBus a;
  SocketCanBus b;
  SocketCanConfig cfg;
  cfg.interface = kInterface;
  cfg.fd = true;
  std::string err;
  if (!a.open(cfg, &err)) {
    WARN("CAN FD not available on " << kInterface << ": " << err);
    return;
  }
  REQUIRE(b.open(cfg, &err));
  CHECK(a.fdEnabled());
  mrqp_fw_frame f = classic(0x140, 0);
  f.len = 64;
  f.flags = MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS;
  f.data[63] = 0xA5;
  REQUIRE(a.send(f) == SendResult::Ok);
  RxFrame rx;
  REQUIRE(receiveOne(b, rx));
  CHECK(rx.frame.len == 64u);
  CHECK(rx.frame.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  CHECK(rx.frame.data[63] == 0xA5);
  // A classic socket refuses FD frames.
  SocketCanBus c;
  cfg.fd = false;
  REQUIRE(c.open(cfg, &err));
  CHECK(c.send(f) == SendResult::Invalid);
}

TEST_CASE("drivers: vcan: a full send buffer is QueueFull, counted, never blocking",
          "[drivers][socketcan][vcan]") {
  SocketCanBus a;
  SocketCanConfig cfg;
  cfg.interface = kInterface;
  cfg.send_buffer_bytes = 1;  // the kernel's minimum
  std::string err;
  REQUIRE(a.open(cfg, &err));
  // vcan forwards immediately, so the queue rarely fills; when it does the result must be
  // QueueFull (ENOBUFS / EAGAIN), counted, and the call must not block.
  int full = 0;
  for (int i = 0; i < 100000 && full == 0; ++i) {
    const SendResult r = a.send(classic(0x100, 8));
    REQUIRE((r == SendResult::Ok || r == SendResult::QueueFull));
    full += r == SendResult::QueueFull ? 1 : 0;
  }
  CHECK(a.status().tx_queue_full == static_cast<std::uint64_t>(full));
}

TEST_CASE("drivers: vcan: the router drains a real socket", "[drivers][socketcan][vcan]") {
  struct Count final : FrameHandler {
    Claim onFrame(const BusRouter&, const RxFrame& rx, TimeNs) noexcept override {
      if (rx.frame.id == 0x081) {
        ++n;
        return Claim::Accepted;
      }
      return Claim::NotMine;
    }
    int n = 0;
  } count;
  SocketCanBus a;
  SocketCanBus b;
  SocketCanConfig cfg;
  cfg.interface = kInterface;
  std::string err;
  REQUIRE(a.open(cfg, &err));
  REQUIRE(b.open(cfg, &err));
  BusRouter router(b);
  REQUIRE(router.addHandler(count));
  for (int i = 0; i < 10; ++i) {
    REQUIRE(a.send(classic(0x081, 8)) == SendResult::Ok);
  }
  REQUIRE(a.send(classic(0x7E0, 1)) == SendResult::Ok);
  ::usleep(20000);
  router.poll(monotonicNow());
  CHECK(count.n == 10);
  CHECK(router.stats().unknown == 1u);
}

namespace {

// Runs before Catch's main: skip (exit 77) where SocketCAN or vcan0 is missing.
struct SkipWithoutVcan {
  SkipWithoutVcan() {
    const int s = ::socket(PF_CAN, SOCK_RAW, 1 /* CAN_RAW */);
    if (s < 0) {
      std::printf(
          "SKIP: AF_CAN not supported by this kernel (socket(AF_CAN, SOCK_RAW, CAN_RAW): %s); "
          "run this test in the HIL VM or on a kernel with CAN and vcan\n",
          std::strerror(errno));
      std::fflush(stdout);
      std::_Exit(77);
    }
    ::close(s);
    if (if_nametoindex(kInterface) == 0) {
      std::printf(
          "SKIP: no %s interface (modprobe vcan; ip link add dev %s type vcan; ip link set %s mtu 72 up)\n",
          kInterface, kInterface, kInterface);
      std::fflush(stdout);
      std::_Exit(77);
    }
  }
};
const SkipWithoutVcan skip_without_vcan;

}  // namespace

TEST_CASE("drivers: vcan: TX echo with receive_own, in wire order, marked own",
          "[drivers][socketcan][vcan]") {
  SocketCanBus a;
  SocketCanBus b;
  SocketCanConfig ca;
  ca.interface = kInterface;
  ca.receive_own = true;
  SocketCanConfig cb;
  cb.interface = kInterface;
  std::string err;
  REQUIRE(a.open(ca, &err));
  REQUIRE(b.open(cb, &err));
  CHECK(a.echoesOwn());
  CHECK_FALSE(b.echoesOwn());
  REQUIRE(a.send(classic(0x000, 2)) == SendResult::Ok);  // a's frame first...
  RxFrame rx;
  REQUIRE(receiveOne(b, rx));
  CHECK_FALSE(rx.own);
  REQUIRE(b.send(classic(0x701, 1)) == SendResult::Ok);  // ... then b's
  REQUIRE(receiveOne(a, rx));
  CHECK(rx.own);  // a's own frame, returned (MSG_CONFIRM), before b's
  CHECK(rx.frame.id == 0x000u);
  REQUIRE(receiveOne(a, rx));
  CHECK_FALSE(rx.own);
  CHECK(rx.frame.id == 0x701u);
  // b does not receive its own frame.
  RxFrame none;
  CHECK(b.receive(none) == ReceiveResult::Empty);
}
