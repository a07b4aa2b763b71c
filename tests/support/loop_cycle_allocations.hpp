// The counted cycles of the loop's allocation tests: a warm-up (the first solves), then `cycles`
// cycles of a booted set-up in which only the controller's cycle is counted by the replaced global
// allocator (counting_allocator.hpp); the plant's following switch, the emulated rig and the clock
// advance outside the count, as each set-up's own cycle() does.
//
// A set-up is any test rig with the members `ctrl` (loop::Controller*), `plant` (a plant wrapper
// with inner().setFollowing), `rig` (loop::EmulatedRig*), `now`, `period` and cycle() (e.g.
// tests/force/force_setup.hpp, tests/estimation/estimation_loop_setup.hpp).
#pragma once

#include "counting_allocator.hpp"

namespace mrqp::testing {

/// Runs `warmup` uncounted cycles, then `cycles` counted ones; returns the allocations counted.
template <class Setup>
long loopCycleAllocations(Setup& s, int cycles, int warmup = 10) {
  for (int k = 0; k < warmup; ++k) s.cycle();
  long counted = 0;
  for (int k = 0; k < cycles; ++k) {
    counted += allocationsIn([&] { s.ctrl->cycle(s.now); });
    s.plant->inner().setFollowing(!s.ctrl->safeStopped());
    s.rig->advanceTo(s.now + s.period);
    s.now += s.period;
  }
  return counted;
}

}  // namespace mrqp::testing
