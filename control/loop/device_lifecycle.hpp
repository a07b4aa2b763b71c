// The devices' boot and safe exit around the control cycle (docs/loop.md, "Safety"): one place
// for what every program and test that runs the controller does before its first cycle and after
// its last.
//
// bootDevices: startDevices, then Controller::bootCycle until every device is booted and enabled
// (or the time limit); after each boot cycle the emulated rig, when there is one, runs to the next
// cycle time. exitDevices: Controller::requestSafeExit, then Controller::exitCycle until every
// device is stopped (arm drives: quick stop or disable voltage, then NMT pre-operational or stop,
// as the hardware section's safe_exit says; the other devices disabled) or the time limit.
//
// The next cycle time comes from `next` when given (a paced program waits for its deadline
// there), else it is now + period. Not real time (called outside the cycle).
#pragma once

#include "loop/controller.hpp"
#include "loop/device_cycles.hpp"
#include "loop/emulated_rig.hpp"

namespace mrqp::loop {

/// Boots and enables every device of `controller`; `now` is advanced cycle by cycle.
LifecycleResult bootDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig = nullptr, double timeout_s = 10.0,
                            const NextCycleTime& next = NextCycleTime());

/// The safe exit of every device of `controller` (see the top of this file).
LifecycleResult exitDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig = nullptr, double timeout_s = 2.0,
                            const NextCycleTime& next = NextCycleTime());

}  // namespace mrqp::loop
