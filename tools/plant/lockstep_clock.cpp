// The lock-step clock of mrqp-plant (see lockstep_clock.hpp).
#include "lockstep_clock.hpp"

#include <stdexcept>
#include <utility>

namespace mrqp::plant {

LockstepClock::LockstepClock(std::vector<drivers::TimeNs> sync_periods)
    : period_(std::move(sync_periods)),
      time_(period_.size(), 0),
      syncs_(period_.size(), 0),
      locked_(period_.size(), 0) {
  for (drivers::TimeNs p : period_) {
    if (p <= 0) throw std::invalid_argument("lock-step clock: a SYNC period must be positive");
  }
}

drivers::TimeNs LockstepClock::onSync(std::size_t b) noexcept {
  if (locked_[b] == 0u) {
    locked_[b] = 1;
    ++locked_count_;
  }
  ++syncs_[b];
  time_[b] += period_[b];
  follow(time_[b]);
  return time_[b];
}

bool LockstepClock::onWall(drivers::TimeNs wall) noexcept {
  bool moved = false;
  for (std::size_t b = 0; b < time_.size(); ++b) {
    if (locked_[b] != 0u || wall <= time_[b]) continue;
    time_[b] = wall;
    follow(wall);
    moved = true;
  }
  return moved;
}

}  // namespace mrqp::plant
