// mrqp drivers -- inertial measurement units (firmware_if/imu.h) on a CAN FD bus.
//
// An IMU samples on SYNC (produced by another driver on the same bus, or by this one with
// produce_sync) and answers with one 24-byte CAN FD frame (0x180 + node, CRC-16). The driver,
// like the F/T driver:
//  - checks every frame (FD, length, CRC, reserved bits, the quaternion's norm: the firmware_if
//    unpack); a corrupt frame is counted and dropped, the previous sample stays;
//  - counts gaps in the sample sequence (lost samples), flags missing samples for N cycles
//    (feedback missing: the IMU is silent or only repeats STALE samples), status FAULT (device
//    fault), OVERRANGE or rate / specific force beyond the configured limits (out of range),
//    TEMPERATURE, STALE or ALIGNING (warning);
//  - publishes orientation, angular rate and specific force in SI units.
// A sample with status ALIGNING (the attitude filter has not converged) is published but the IMU
// is not ready() until one without it has arrived.
//
// Cycle: BusRouter::poll, update(now), imu(i), transmit(now). Real-time safe after create().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/device.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/router_attachment.hpp"
#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/imu.h"

namespace mrqp::drivers {

struct ImuSensorConfig {
  std::size_t bus = 0;    ///< index into the routers given to create(); the bus must be CAN FD
  std::uint8_t node = 1;  ///< 1..127
  mrqp_fw_imu_scale scale = MRQP_FW_IMU_SCALE_DEFAULT_INIT;
  double rate_limit = std::numeric_limits<double>::infinity();   ///< rad/s, per axis (feedback check)
  double force_limit = std::numeric_limits<double>::infinity();  ///< m/s^2, per axis
};

struct ImuConfig {
  std::vector<ImuSensorConfig> imus;
  bool produce_sync = false;  ///< send one SYNC per bus and cycle
  std::uint32_t feedback_missing_cycles = 3;
};

struct ImuState {
  std::array<double, 4> orientation{{1.0, 0.0, 0.0, 0.0}};  ///< w x y z
  std::array<double, 3> angular_velocity{};                 ///< rad/s
  std::array<double, 3> specific_force{};                   ///< m/s^2
  std::uint8_t seq = 0;
  std::uint8_t status = 0;  ///< MRQP_FW_IMU_STATUS_*
  bool valid = false;       ///< a sample has been received
  bool aligned = false;     ///< a sample without ALIGNING has been received
  bool fresh = false;       ///< a new (not STALE) sample arrived since the previous update()
  TimeNs timestamp = 0;
};

class ImuDriver final : public ImuDevice, public FrameHandler {
 public:
  static std::unique_ptr<ImuDriver> create(const std::vector<BusRouter*>& buses, const ImuConfig& config,
                                           std::string* error);
  ImuDriver(const ImuDriver&) = delete;
  ImuDriver& operator=(const ImuDriver&) = delete;

  const char* kind() const noexcept override { return "imu"; }
  /// Starts monitoring (missing samples are counted from here) and SYNC production.
  void start(TimeNs now) noexcept override;
  /// Started, and every IMU has sent an aligned sample.
  bool ready() const noexcept override;
  const FaultReport& update(TimeNs now) noexcept override;
  std::size_t transmit(TimeNs now) noexcept override;
  const FaultReport& faults() const noexcept override { return routers_.report(); }
  void declareTraffic(std::size_t bus, BusBudget& budget) const override;

  std::size_t imuCount() const noexcept override { return imus_.size(); }
  ImuFeedback imu(std::size_t i) const noexcept override;
  const ImuState& state(std::size_t i) const noexcept { return imus_[i].state; }

  Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;

 private:
  struct Imu {
    ImuSensorConfig cfg;
    ImuState state;
    DeviceFaults faults;
    std::uint32_t events = 0;
    bool got_sample = false;
    bool seq_valid = false;
  };
  struct BusSlot {
    std::array<std::int16_t, 128> node_to_imu{};
    bool has_imus = false;
  };
  ImuDriver() = default;

  ImuConfig config_;
  std::vector<Imu> imus_;
  std::vector<BusSlot> buses_;
  bool started_ = false;
  RouterAttachment routers_;
};

}  // namespace mrqp::drivers
