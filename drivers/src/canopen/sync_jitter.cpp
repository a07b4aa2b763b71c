// mrqp drivers -- CANopen master, SYNC interval and jitter of one bus (see canopen/sync_jitter.hpp).
#include "mrqp/drivers/canopen/sync_jitter.hpp"

namespace mrqp::drivers {

void SyncJitter::init(TimeNs period, double timeout_factor) noexcept {
  stats_ = SyncStats{};
  stats_.period = period;
  stats_.timeout_factor = timeout_factor;
  sum_abs_ = 0.0;
  have_last_ = false;
  last_ = 0;
}

void SyncJitter::onSync(TimeNs t) noexcept {
  ++stats_.syncs;
  if (have_last_) {
    const TimeNs interval = t - last_;
    const TimeNs dev = interval > stats_.period ? interval - stats_.period : stats_.period - interval;
    if (stats_.intervals == 0u || interval < stats_.min_interval) {
      stats_.min_interval = interval;
    }
    if (stats_.intervals == 0u || interval > stats_.max_interval) {
      stats_.max_interval = interval;
    }
    if (dev > stats_.max_jitter) {
      stats_.max_jitter = dev;
    }
    ++stats_.intervals;
    sum_abs_ += static_cast<double>(dev);
    stats_.mean_abs_jitter_ns = sum_abs_ / static_cast<double>(stats_.intervals);
    if (static_cast<double>(interval) > stats_.timeout_factor * static_cast<double>(stats_.period)) {
      ++stats_.over_timeout;
    }
  }
  have_last_ = true;
  last_ = t;
}

}  // namespace mrqp::drivers
