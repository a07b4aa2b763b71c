// What mrqp-stream watches while it streams (see stream_monitor.hpp).
#include "stream_monitor.hpp"

#include <mrqp/drivers/canopen/canopen_text.hpp>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mrqp::stream {

using namespace mrqp::drivers;

StreamMonitor::StreamMonitor(std::size_t drives, double max_error, int expect_hb_drive)
    : max_error_(max_error),
      hb_drive_(expect_hb_drive),
      sent_(drives, 0.0),
      max_err_(drives, 0.0),
      hb_lost_wall_(drives, -1.0),
      hb_lost_(drives, 0),
      hb_lost_at_(drives, -1),
      reported_(drives, 0),
      events_(64) {}  // the first faults of each kind per drive, in order

void StreamMonitor::note(const FaultReport& r) noexcept {
  all_flags_ |= r.flags;
  for (std::size_t j = 0; j < sent_.size() && j < r.device_count; ++j) {
    const std::uint32_t fresh = r.devices[j].flags & ~reported_[j] &
                                (fault::kEmcy | fault::kStateMismatch | fault::kBootFailed | fault::kTimeout |
                                 fault::kHeartbeatLost | fault::kDeviceFault | fault::kRecovering);
    if (fresh != 0u && event_count_ < events_.size())
      events_[event_count_++] = Event{cycle_, j, r.devices[j]};
    reported_[j] |= fresh;
  }
}

void StreamMonitor::check(long k, TimeNs since_start, const FaultReport& r, const ArmDriver& arm) noexcept {
  constexpr std::uint32_t kHard = fault::kFeedbackMissing | fault::kDeviceFault | fault::kBootFailed |
                                  fault::kTimeout | fault::kHeartbeatLost | fault::kStateMismatch |
                                  fault::kBusOff;
  std::uint32_t cycle_fail = 0;
  for (std::size_t j = 0; j < sent_.size(); ++j) {
    const DeviceFaults& df = r.devices[j];
    if ((df.flags & fault::kHeartbeatLost) != 0u) {
      ++hb_lost_[j];
      if (hb_lost_at_[j] < 0) {
        hb_lost_at_[j] = since_start;
        timespec wall;
        clock_gettime(CLOCK_REALTIME, &wall);
        hb_lost_wall_[j] = static_cast<double>(wall.tv_sec) + static_cast<double>(wall.tv_nsec) * 1e-9;
      }
    }
    if (static_cast<int>(j) == hb_drive_ && hb_lost_at_[j] >= 0) continue;  // the loss the run is about
    cycle_fail |= df.flags & kHard;
    const ArmDriveState& s = arm.drive(j);
    if (k > 0 && s.valid) {
      const double e = std::fabs(s.position - sent_[j]);
      max_err_[j] = std::max(max_err_[j], e);
      if (e > max_error_) cycle_fail |= fault::kOutOfRange;
    }
  }
  if (cycle_fail != 0u) {
    ++fail_cycles_;
    fail_flags_ |= cycle_fail;
  }
}

void StreamMonitor::printEvents() const {
  for (std::size_t e = 0; e < event_count_; ++e) {
    std::printf("mrqp-stream: cycle %ld: drive %zu: %s\n", events_[e].cycle, events_[e].drive,
                describeDeviceFaults(events_[e].faults).c_str());
  }
}

void StreamMonitor::printPhases() const {
  std::printf(
      "mrqp-stream: phases: read_mean_us=%.1f read_max_us=%.1f write_mean_us=%.1f write_max_us=%.1f\n",
      phases_.mean(kRead) / 1e3, static_cast<double>(phases_.max(kRead)) / 1e3, phases_.mean(kWrite) / 1e3,
      static_cast<double>(phases_.max(kWrite)) / 1e3);
}

void StreamMonitor::printDrives(const ArmConfig& cfg, const std::vector<DeviceFaults>& faults) const {
  for (std::size_t j = 0; j < sent_.size(); ++j) {
    const DeviceFaults& df = faults[j];
    std::printf(
        "mrqp-stream: node %u: max_error=%.5f rad emcy_count=%u emcy_code=0x%04x corrupt_frames=%u "
        "heartbeat_lost_cycles=%llu heartbeat_lost_at_ms=%.1f tolerated_aborts=%u recoveries=%u nmt=%s\n",
        cfg.drives[j].node, max_err_[j], df.emcy_count, df.emcy_code, df.corrupt_frames,
        static_cast<unsigned long long>(hb_lost_[j]),
        hb_lost_at_[j] < 0 ? -1.0 : static_cast<double>(hb_lost_at_[j]) / 1e6, df.tolerated_aborts,
        df.recoveries, nmtStateStr(df.nmt_state));
  }
}

void StreamMonitor::printHeartbeatLoss(std::size_t j, int node, int timeout_ms) const {
  std::printf(
      "mrqp-stream: heartbeat loss of node %d detected at %.1f ms of streaming, wall %.6f, timeout %d ms\n",
      node, static_cast<double>(hb_lost_at_[j]) / 1e6, hb_lost_wall_[j], timeout_ms);
}

}  // namespace mrqp::stream
