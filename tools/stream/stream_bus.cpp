// The bus mrqp-stream streams on (see stream_bus.hpp).
#include "stream_bus.hpp"

namespace mrqp::stream {

using namespace mrqp::drivers;

bool StreamBus::open(const Options& o, std::string* err) {
  if (o.interface != "sim") {
    SocketCanConfig sc;
    sc.interface = o.interface;
    sc.receive_own = true;  // the arm master takes a boot-up only after its reset's own echo
    return can_.open(sc, err);
  }
  drive_emu::EmuConfig emu;
  if (!o.yaml.empty()) {
    if (!drive_emu::loadConfig(o.yaml, &emu, err)) return false;
  } else {
    for (std::uint8_t n : o.nodes) {
      drive_emu::EmuNode node;
      node.node = n;
      emu.nodes.push_back(node);
    }
  }
  sim_ = std::make_unique<SimBus>();
  SimNodeConfig mc;
  mc.name = "mrqp-stream";
  mc.rx_queue = 4096;
  mc.echo_own = true;
  master_ = sim_->addNode(mc);
  SimNodeConfig ec;
  ec.name = "mrqp-drive-emu";
  ec.rx_queue = 4096;
  ec.tx_queue = 1024;
  emulator_ = std::make_unique<drive_emu::SimDriveEmulator>(*sim_->addNode(ec), emu);
  return true;
}

Bus& StreamBus::bus() noexcept {
  if (master_ != nullptr) return *master_;
  return can_;
}

TimeNs StreamBus::start() noexcept {
  if (!simulated()) return clock_.start();
  t_ = sim_->now();
  return t_;
}

TimeNs StreamBus::next() noexcept {
  if (!simulated()) return clock_.wait();
  t_ += period_;
  sim_->advanceTo(t_);
  return t_;
}

}  // namespace mrqp::stream
