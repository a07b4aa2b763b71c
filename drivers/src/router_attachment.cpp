// mrqp drivers -- a driver's routers, bus health and fault report: the real-time part.
#include "mrqp/drivers/router_attachment.hpp"

namespace mrqp::drivers {

int RouterAttachment::slotOf(const BusRouter& router) const noexcept {
  for (std::size_t i = 0; i < routers_.size(); ++i) {
    if (routers_[i] == &router) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void RouterAttachment::startCycle() noexcept {
  ++report_.cycle;
  for (std::size_t s = 0; s < routers_.size(); ++s) {
    bus_faults_[s] = health_[s].update(*routers_[s]);
  }
}

const FaultReport& RouterAttachment::publish() noexcept {
  report_.devices = device_faults_.data();
  report_.device_count = device_faults_.size();
  report_.buses = bus_faults_.data();
  report_.bus_count = bus_faults_.size();
  std::uint32_t flags = 0;
  for (const DeviceFaults& d : device_faults_) {
    flags |= d.flags;
  }
  for (const BusFaults& b : bus_faults_) {
    flags |= b.flags;
  }
  report_.flags = flags;
  return report_;
}

}  // namespace mrqp::drivers
