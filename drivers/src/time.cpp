// mrqp drivers -- the monotonic clock.
#include "mrqp/drivers/time.hpp"

#include <ctime>

namespace mrqp::drivers {

TimeNs monotonicNow() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * 1000000000 + static_cast<TimeNs>(ts.tv_nsec);
}

}  // namespace mrqp::drivers
