// mrqp drivers -- wrist force/torque sensors (firmware_if/ft_sensor.h), usually on the arm bus.
//
// A sensor samples on SYNC (produced by the arm driver on the same bus, or by this driver with
// produce_sync) and answers with either the classic pair (forces on 0x180 + node, moments on
// 0x280 + node, same seq and status) or one CAN FD frame (0x180 + node, CRC-16). The driver:
//  - joins the two halves of a classic pair; halves whose seq/status differ, or a half whose
//    partner has not arrived by the next update, are a torn pair: counted, dropped, no sample;
//  - checks the FD frame (CRC, padding, reserved bits: firmware_if unpack): corrupt -> dropped;
//  - counts gaps in the sample sequence (lost samples), flags missing samples for N cycles,
//    status over-range (out of range), fault (device fault), temperature / stale (warning), and
//    wrench components beyond the configured limits;
//  - sends tare / clear-tare commands (retried while the queue is full) and confirms them with
//    the status bit "tared".
//
// Cycle: BusRouter::poll, update(now), requestTare(), transmit(now). Real-time safe after create().
// As a WrenchDevice (device.hpp) sensor i is the configured sensor i; ready() once started and
// every sensor has delivered a sample.
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
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/ft_sensor.h"

namespace mrqp::drivers {

enum class FtVariant : std::uint8_t { Classic = 0, Fd };

struct FtSensorConfig {
  std::size_t bus = 0;    ///< index into the routers given to create()
  std::uint8_t node = 1;  ///< 1..127 (its own node id on the arm bus)
  FtVariant variant = FtVariant::Classic;
  mrqp_fw_ft_scale scale = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;  ///< use the FD default for Fd
  double force_limit = std::numeric_limits<double>::infinity();    ///< N, per axis (feedback check)
  double moment_limit = std::numeric_limits<double>::infinity();   ///< N m, per axis
};

struct FtConfig {
  std::vector<FtSensorConfig> sensors;
  bool produce_sync = false;  ///< send one SYNC per bus and cycle (no arm driver there)
  std::uint32_t feedback_missing_cycles = 3;
  TimeNs tare_timeout = milliseconds(100);
};

struct FtSensorState {
  std::array<double, 6> wrench{};  ///< fx fy fz (N), mx my mz (N m), sensor frame
  std::uint8_t seq = 0;
  std::uint8_t status = 0;  ///< MRQP_FW_FT_STATUS_*
  bool valid = false;       ///< a sample has been received
  bool fresh = false;       ///< a new sample arrived since the previous update()
  TimeNs timestamp = 0;     ///< reception time of the frame that completed the sample
};

class FtSensorDriver final : public WrenchDevice, public FrameHandler {
 public:
  static std::unique_ptr<FtSensorDriver> create(const std::vector<BusRouter*>& buses, const FtConfig& config,
                                                std::string* error);
  FtSensorDriver(const FtSensorDriver&) = delete;
  FtSensorDriver& operator=(const FtSensorDriver&) = delete;

  const char* kind() const noexcept override { return "ft"; }
  /// Starts monitoring (missing samples are counted from here) and SYNC production.
  void start(TimeNs now) noexcept override;
  bool ready() const noexcept override;
  /// Tare (true) or clear the tare (false) of sensor i at the next transmit().
  bool requestTare(std::size_t sensor, bool tare, TimeNs now) noexcept;

  const FaultReport& update(TimeNs now) noexcept override;
  std::size_t transmit(TimeNs now) noexcept override;

  Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;

  std::size_t sensorCount() const noexcept override { return sensors_.size(); }
  WrenchFeedback wrench(std::size_t sensor) const noexcept override;
  const FtSensorState& sensor(std::size_t i) const noexcept { return sensors_[i].state; }
  /// True while a tare command has not been confirmed by the status bit.
  bool tarePending(std::size_t i) const noexcept { return sensors_[i].tare_wait; }
  const FaultReport& faults() const noexcept override { return routers_.report(); }
  void declareTraffic(std::size_t bus, BusBudget& budget) const override;

 private:
  struct Half {
    mrqp_fw_ft_half half{};
    bool present = false;
    bool waited = false;        ///< already pending at the previous update
    std::uint64_t arrival = 0;  ///< order of arrival
    TimeNs time = 0;
  };
  struct Sensor {
    FtSensorConfig cfg;
    FtSensorState state;
    DeviceFaults faults;
    std::uint32_t events = 0;
    Half forces;
    Half moments;
    bool got_sample = false;
    bool seq_valid = false;
    bool tare_send = false;  ///< a tare frame is waiting for the queue
    bool tare_wait = false;  ///< waiting for the status to confirm
    bool tare_value = false;
    TimeNs tare_since = 0;
  };
  struct BusSlot {
    std::array<std::int16_t, 128> node_to_sensor{};
    bool has_sensors = false;
  };
  FtSensorDriver() = default;
  void publishSample(Sensor& s, const mrqp_fw_ft_sample& sample, TimeNs t) noexcept;
  Claim onHalf(Sensor& s, const mrqp_fw_frame& f, TimeNs t) noexcept;

  FtConfig config_;
  std::vector<Sensor> sensors_;
  std::vector<BusSlot> buses_;
  bool started_ = false;
  std::uint64_t arrivals_ = 0;
  RouterAttachment routers_;
};

}  // namespace mrqp::drivers
