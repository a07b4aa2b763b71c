// mrqp drivers -- a driver's routers, bus health and fault report: registration (setup).
#include "mrqp/drivers/router_attachment.hpp"

namespace mrqp::drivers {

std::string RouterAttachment::attach(const std::vector<BusRouter*>& routers, FrameHandler& handler,
                                     std::size_t devices) {
  device_faults_.resize(devices);
  bus_faults_.resize(routers.size());
  health_.resize(routers.size());
  for (std::size_t s = 0; s < routers.size(); ++s) {
    bool duplicate = false;
    for (std::size_t k = 0; k < s; ++k) {
      duplicate = duplicate || routers[k] == routers[s];
    }
    // A router refuses a handler it already has: a bus given twice is named as such.
    if (duplicate || !routers[s]->addHandler(handler)) {
      for (std::size_t k = 0; k < s; ++k) {
        routers[k]->removeHandler(handler);
      }
      return "bus " + std::to_string(s) +
             (duplicate ? " given twice" : ": the router's handler table is full");
    }
    health_[s].reset(*routers[s]);
  }
  handler_ = &handler;
  routers_ = routers;
  report_.devices = device_faults_.data();
  report_.device_count = device_faults_.size();
  report_.buses = bus_faults_.data();
  report_.bus_count = bus_faults_.size();
  return {};
}

RouterAttachment::~RouterAttachment() {
  if (handler_ == nullptr) {
    return;
  }
  for (BusRouter* r : routers_) {
    r->removeHandler(*handler_);
  }
}

}  // namespace mrqp::drivers
