// mrqp emulation -- one IMU's firmware (firmware_if/imu.h), transport-free.
//
// On every SYNC the IMU reads orientation, angular rate and specific force from the host and
// answers after the response delay with its CAN FD sample frame (0x180 + node), seq + 1 per
// SYNC, status ALIGNING until `align_until` (the attitude filter converging after power-on).
//
// Fault switches: setSilent() (no samples), corruptSamples(n) (the next n frames with a
// flipped bit: CRC error), setStale() (the last values repeated with status STALE),
// raiseFault() / clearFault() (status FAULT). No allocation.
#pragma once

#include <array>
#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/imu.h"

namespace mrqp::emulation {

using drivers::TimeNs;

/// What the IMU measures, in its own frame.
struct ImuValues {
  std::array<double, 4> orientation{{1.0, 0.0, 0.0, 0.0}};  ///< w x y z: sensor frame in the world
  std::array<double, 3> angular_velocity{};                 ///< rad/s
  std::array<double, 3> specific_force{};                   ///< m/s^2 (at rest: +9.81 along "up")
};

class EmulatedImu {
 public:
  struct Options {
    std::uint8_t node = 1;  ///< 1..127
    mrqp_fw_imu_scale scale = MRQP_FW_IMU_SCALE_DEFAULT_INIT;
    TimeNs response_delay = 15000;
    TimeNs align_until = 0;  ///< status ALIGNING for samples before this time
  };

  class Host {
   public:
    virtual void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept = 0;
    virtual ImuValues imu(TimeNs now) noexcept = 0;

   protected:
    ~Host() = default;
  };

  EmulatedImu(Host& host, const Options& options) noexcept;
  EmulatedImu(const EmulatedImu&) = delete;
  EmulatedImu& operator=(const EmulatedImu&) = delete;

  /// A frame on the bus at `now`; true if it was a SYNC.
  bool onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  void advance(TimeNs) noexcept {}
  TimeNs nextEvent() const noexcept { return INT64_MAX; }

  // ---- fault injection ----
  void setSilent(bool silent) noexcept { silent_ = silent; }
  void corruptSamples(unsigned n) noexcept { corrupt_left_ = n; }
  void setStale(bool stale) noexcept { stale_ = stale; }
  void raiseFault() noexcept { faulted_ = true; }
  void clearFault() noexcept { faulted_ = false; }

  unsigned syncs() const noexcept { return syncs_; }

 private:
  Host& host_;
  Options options_;
  ImuValues last_{};
  std::uint8_t seq_ = 0;
  unsigned syncs_ = 0;
  unsigned corrupt_left_ = 0;
  bool have_last_ = false;
  bool silent_ = false;
  bool stale_ = false;
  bool faulted_ = false;
};

}  // namespace mrqp::emulation
