// SocketCAN back end, part that runs everywhere: on a kernel without AF_CAN open() must fail
// with a clear message; a closed bus refuses to send and has nothing to receive.
#include <catch2/catch.hpp>

#include <mrqp/drivers/socketcan_bus.hpp>

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <string>

using namespace mrqp::drivers;

namespace {

bool kernelHasAfCan() {
  const int s = ::socket(PF_CAN, SOCK_RAW, 1 /* CAN_RAW */);
  if (s < 0) {
    return false;
  }
  ::close(s);
  return true;
}

}  // namespace

TEST_CASE("drivers: SocketCAN: open() explains a kernel without AF_CAN", "[drivers][socketcan]") {
  SocketCanBus bus;
  SocketCanConfig cfg;
  cfg.interface = "vcan0";
  std::string err;
  const bool ok = bus.open(cfg, &err);
  if (kernelHasAfCan()) {
    WARN(
        "this kernel has AF_CAN: the no-AF_CAN message is not exercised here (see "
        "test_drivers_socketcan_vcan)");
    if (!ok) {
      CHECK_THAT(err, Catch::Matchers::Contains("vcan0"));  // e.g. no such interface
    }
    return;
  }
  CHECK(!ok);
  CHECK(!bus.isOpen());
  CHECK_THAT(err, Catch::Matchers::StartsWith("AF_CAN not supported by this kernel"));
  CHECK_THAT(err, Catch::Matchers::Contains("socket(AF_CAN, SOCK_RAW, CAN_RAW)"));
  CHECK_THAT(err, Catch::Matchers::Contains("SimBus"));
}

TEST_CASE("drivers: SocketCAN: a closed bus refuses to send and receives nothing", "[drivers][socketcan]") {
  SocketCanBus bus;
  mrqp_fw_frame f{};
  f.id = 0x123;
  f.len = 1;
  CHECK(bus.send(f) == SendResult::Down);
  RxFrame rx;
  CHECK(bus.receive(rx) == ReceiveResult::Empty);
  CHECK(bus.status().tx_failed == 1u);
  CHECK(!bus.fdEnabled());
  SocketCanConfig bad;
  bad.interface = "";
  std::string err;
  CHECK(!bus.open(bad, &err));
  CHECK_THAT(err, Catch::Matchers::Contains("invalid interface name"));
  bad.interface = "an-interface-name-too-long";
  CHECK(!bus.open(bad, &err));
}
