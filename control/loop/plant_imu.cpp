// An emulated IMU on the plant (see plant_imu.hpp).
#include "loop/plant_imu.hpp"

namespace mrqp::loop {

namespace {
emulation::EmulatedImu::Options imuOptions(std::uint8_t node) noexcept {
  emulation::EmulatedImu::Options o;
  o.node = node;
  return o;
}
}  // namespace

PlantImu::PlantImu(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id)
    : node_(node), plant_(plant), frame_(frame), imu_(*this, imuOptions(node_id)) {
  node_.set_listener(this);
}

void PlantImu::emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept {
  (void)node_.send_at(frame, at);
}

emulation::ImuValues PlantImu::imu(drivers::TimeNs) noexcept {
  const ImuSample s = plant_.imu(frame_);
  emulation::ImuValues v;
  v.orientation = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
  v.angular_velocity = {s.angular_velocity.x(), s.angular_velocity.y(), s.angular_velocity.z()};
  v.specific_force = {s.specific_force.x(), s.specific_force.y(), s.specific_force.z()};
  return v;
}

void PlantImu::on_receive(drivers::SimNode&, drivers::ReceiveResult kind,
                          const drivers::RxFrame& rx) noexcept {
  if (kind == drivers::ReceiveResult::Frame) (void)imu_.on_frame(rx.frame, rx.timestamp);
}

}  // namespace mrqp::loop
