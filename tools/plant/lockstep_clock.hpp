// The lock-step clock of `mrqp-plant --clock sync` (docs/loop.md, "Controller and plant in two
// processes"): the time of each simulated bus of the rig, and so of the emulated firmware and the
// plant, as SIL/HIL simulators keep it on machines that cannot keep real time.
//
// A bus runs on the wall clock until the controller's first SYNC on it (the boot: SDO, NMT); from
// that SYNC on it is locked: each SYNC of the controller on it runs it by exactly one SYNC period
// (its robot's divisor × the loop period), whatever the wall clock did meanwhile, so that the drives
// answer every SYNC as they would at SYNC on a real bus and a stall of the machine (both processes
// frozen) costs the plant no time the controller did not run. The plant follows the latest bus.
// Real-time safe after construction (no allocation).
#pragma once

#include <mrqp/drivers/time.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrqp::plant {

class LockstepClock {
 public:
  /// sync_periods[b]: the SYNC period of bus b (ns, > 0).
  explicit LockstepClock(std::vector<drivers::TimeNs> sync_periods);

  std::size_t busCount() const noexcept { return time_.size(); }
  bool locked(std::size_t b) const noexcept { return locked_[b] != 0u; }
  bool allLocked() const noexcept { return locked_count_ == time_.size(); }
  /// Bus b's time: what it has been run to.
  drivers::TimeNs busTime(std::size_t b) const noexcept { return time_[b]; }
  /// The plant's time: the latest bus time.
  drivers::TimeNs plantTime() const noexcept { return plant_; }
  /// SYNCs seen on bus b since it locked.
  std::uint64_t syncs(std::size_t b) const noexcept { return syncs_[b]; }

  /// A SYNC of the controller on bus b (already handed to the bus at busTime(b)): locks the bus
  /// on its first and returns the time to run it to, one SYNC period later.
  drivers::TimeNs onSync(std::size_t b) noexcept;
  /// The wall clock (ns since the start) moves every bus not locked yet; returns true when one moved.
  bool onWall(drivers::TimeNs wall) noexcept;

 private:
  void follow(drivers::TimeNs t) noexcept {
    if (t > plant_) plant_ = t;
  }
  std::vector<drivers::TimeNs> period_;
  std::vector<drivers::TimeNs> time_;
  std::vector<std::uint64_t> syncs_;
  std::vector<unsigned char> locked_;
  std::size_t locked_count_ = 0;
  drivers::TimeNs plant_ = 0;
};

}  // namespace mrqp::plant
