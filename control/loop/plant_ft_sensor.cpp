// An emulated F/T sensor on the plant (see plant_ft_sensor.hpp).
#include "loop/plant_ft_sensor.hpp"

namespace mrqp::loop {

namespace {
emulation::EmulatedFtSensor::Options sensorOptions(std::uint8_t node) noexcept {
  emulation::EmulatedFtSensor::Options o;
  o.node = node;
  return o;
}
}  // namespace

PlantFtSensor::PlantFtSensor(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id)
    : node_(node), plant_(plant), frame_(frame), sensor_(*this, sensorOptions(node_id)), glue_(node) {
  glue_.add(sensor_);
}

void PlantFtSensor::emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept {
  (void)node_.sendAt(frame, at);
}

std::array<double, 6> PlantFtSensor::wrench(drivers::TimeNs) noexcept {
  const Vector6d w = plant_.sensorWrench(frame_);
  return {w(0), w(1), w(2), w(3), w(4), w(5)};
}

}  // namespace mrqp::loop
