// mrqp drivers -- what every device driver holds about the buses it is registered with: the
// routers, a BusHealth per router, and the fault report over its devices and those buses.
//
// A driver (a FrameHandler) owns one RouterAttachment. create() calls attach() once (setup:
// allocates the fault arrays, registers the driver with every router); the destructor removes
// the driver from the routers again. Each update() calls startCycle() first (this cycle's
// BusFaults), fills device(i), and ends with publish(). Everything but attach() is real-time safe.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mrqp/drivers/bus_health.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/faults.hpp"

namespace mrqp::drivers {

class RouterAttachment {
 public:
  RouterAttachment() = default;
  /// Removes the handler from every router it was registered with.
  ~RouterAttachment();
  RouterAttachment(const RouterAttachment&) = delete;
  RouterAttachment& operator=(const RouterAttachment&) = delete;

  /// Setup: sizes the fault arrays (`devices` devices, one entry per router), registers `handler`
  /// with every router in order and starts their BusHealth. When a router is given twice or its
  /// handler table is full, removes `handler` from the routers already done and returns the
  /// reason naming the bus ("bus 2 given twice"); an empty string on success.
  std::string attach(const std::vector<BusRouter*>& routers, FrameHandler& handler, std::size_t devices);

  std::size_t busCount() const noexcept { return routers_.size(); }
  BusRouter& router(std::size_t bus) const noexcept { return *routers_[bus]; }
  /// Index of `router` among the attached ones, -1 if it is not one of them.
  int slotOf(const BusRouter& router) const noexcept;

  /// Start of update(): counts the cycle and takes this cycle's BusFaults from every router.
  void startCycle() noexcept;
  /// The faults of device `i` in the report (update() writes them each cycle).
  DeviceFaults& device(std::size_t i) noexcept { return device_faults_[i]; }
  /// End of update(): the report's flags, the OR of every device and bus flag of this cycle.
  const FaultReport& publish() noexcept;
  const FaultReport& report() const noexcept { return report_; }

 private:
  FrameHandler* handler_ = nullptr;
  std::vector<BusRouter*> routers_;
  std::vector<BusHealth> health_;
  std::vector<DeviceFaults> device_faults_;
  std::vector<BusFaults> bus_faults_;
  FaultReport report_{};
};

}  // namespace mrqp::drivers
