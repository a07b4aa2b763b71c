// The lock-step clock of mrqp-plant (lockstep_clock.hpp) against the closed form of its schedule:
// a bus follows the wall clock until its first SYNC, then moves by exactly one SYNC period per
// SYNC whatever the wall clock does (a stall of the machine), and the plant follows the latest bus.
#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>

#include "lockstep_clock.hpp"

using mrqp::drivers::TimeNs;
using mrqp::plant::LockstepClock;

namespace {
constexpr TimeNs kMs = 1000000;
}

TEST_CASE("lock-step clock: the wall clock until the first SYNC, one period per SYNC after it",
          "[plant][lockstep]") {
  LockstepClock c({10 * kMs, 5 * kMs});
  CHECK_FALSE(c.locked(0));
  CHECK(c.onWall(37 * kMs));
  CHECK(c.busTime(0) == 37 * kMs);
  CHECK(c.busTime(1) == 37 * kMs);
  CHECK(c.plantTime() == 37 * kMs);
  CHECK_FALSE(c.onWall(30 * kMs));  // the wall clock never moves a bus back
  CHECK(c.busTime(0) == 37 * kMs);

  // Bus 0 locks at its first SYNC: from 37 ms, 10 ms per SYNC.
  CHECK(c.onSync(0) == 47 * kMs);
  CHECK(c.locked(0));
  CHECK_FALSE(c.allLocked());
  // A stall of 5 s: the wall clock moves only the bus still unlocked.
  CHECK(c.onWall(5037 * kMs));
  CHECK(c.busTime(0) == 47 * kMs);
  CHECK(c.busTime(1) == 5037 * kMs);
  CHECK(c.onSync(1) == 5042 * kMs);
  CHECK(c.allLocked());
  CHECK_FALSE(c.onWall(9000 * kMs));

  const TimeNs t0 = c.busTime(0), t1 = c.busTime(1);
  for (int k = 1; k <= 250; ++k) {
    c.onSync(0);
    c.onSync(1);
    c.onSync(1);
    if (k == 100) CHECK_FALSE(c.onWall(60000 * kMs));  // another stall changes nothing
  }
  CHECK(c.busTime(0) == t0 + 250 * 10 * kMs);
  CHECK(c.busTime(1) == t1 + 500 * 5 * kMs);
  CHECK(c.syncs(0) == 251);
  CHECK(c.syncs(1) == 501);
  CHECK(c.plantTime() == std::max(c.busTime(0), c.busTime(1)));
}

TEST_CASE("lock-step clock: a SYNC period must be positive", "[plant][lockstep]") {
  CHECK_THROWS_AS(LockstepClock({10 * kMs, 0}), std::invalid_argument);
}
