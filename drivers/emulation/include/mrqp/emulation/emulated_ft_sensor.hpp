// mrqp emulation -- one wrist force/torque sensor's firmware (firmware_if/ft_sensor.h),
// transport-free.
//
// On every SYNC the sensor reads the wrench at its frame from the host, subtracts its tare and
// answers after the response delay with the classic pair (forces 0x180 + node, moments 0x280 +
// node) or the CAN FD frame (0x180 + node), seq + 1 per SYNC. The tare command (0x200 + node)
// stores the current wrench as the offset (or clears it); the status bit TARED says which.
//
// Fault switches: setSilent() (no samples: feedback missing), corruptSamples(n) (the next n
// samples corrupt: the moments half one byte short, or the FD frame with a flipped bit),
// setStale() (the last values repeated with status STALE: the ADC stopped), raiseFault() /
// clearFault() (status FAULT), dropMoments(n) (only the forces half: torn pairs). No allocation.
#pragma once

#include <array>
#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/ft_sensor.h"

namespace mrqp::emulation {

using drivers::TimeNs;

class EmulatedFtSensor {
 public:
  struct Options {
    std::uint8_t node = 1;  ///< 1..127
    bool fd = false;        ///< the CAN FD frame instead of the classic pair
    mrqp_fw_ft_scale scale = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;  ///< use the FD default with fd
    TimeNs response_delay = 15000;
  };

  class Host {
   public:
    virtual void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept = 0;
    /// The wrench at the sensor frame now: fx fy fz (N), mx my mz (N m).
    virtual std::array<double, 6> wrench(TimeNs now) noexcept = 0;

   protected:
    ~Host() = default;
  };

  EmulatedFtSensor(Host& host, const Options& options) noexcept;
  EmulatedFtSensor(const EmulatedFtSensor&) = delete;
  EmulatedFtSensor& operator=(const EmulatedFtSensor&) = delete;

  /// A frame on the bus at `now`; true if it was a SYNC or a tare command for this sensor.
  bool onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  void advance(TimeNs) noexcept {}
  TimeNs nextEvent() const noexcept { return INT64_MAX; }

  // ---- fault injection ----
  void setSilent(bool silent) noexcept { silent_ = silent; }
  void corruptSamples(unsigned n) noexcept { corrupt_left_ = n; }
  void setStale(bool stale) noexcept { stale_ = stale; }
  void raiseFault() noexcept { faulted_ = true; }
  void clearFault() noexcept { faulted_ = false; }
  void dropMoments(unsigned n) noexcept { drop_moments_ = n; }

  // ---- observation ----
  bool tared() const noexcept { return tared_; }
  unsigned syncs() const noexcept { return syncs_; }
  std::uint8_t seq() const noexcept { return seq_; }

 private:
  void sample(TimeNs now) noexcept;

  Host& host_;
  Options options_;
  std::array<double, 6> last_{};
  std::array<double, 6> offset_{};
  std::uint8_t seq_ = 0;
  unsigned syncs_ = 0;
  unsigned corrupt_left_ = 0;
  unsigned drop_moments_ = 0;
  bool have_last_ = false;
  bool tared_ = false;
  bool silent_ = false;
  bool stale_ = false;
  bool faulted_ = false;
};

}  // namespace mrqp::emulation
