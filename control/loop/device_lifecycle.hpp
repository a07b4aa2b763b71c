// The devices' boot and safe exit around the control cycle (docs/loop.md, "Safety"): one place
// for what every program and test that runs the controller does before its first cycle and after
// its last.
//
// bootDevices: startDevices, then Controller::bootCycle until every device is booted and enabled,
// a device reports that its boot failed (fault::kBootFailed: an SDO abort, a failed identity check,
// no boot-up; waiting longer cannot help) or the time limit; after each boot cycle the emulated
// rig, when there is one, runs to the next cycle time. exitDevices: Controller::requestSafeExit,
// then Controller::exitCycle until every device is stopped (arm drives: quick stop or disable
// voltage, then NMT pre-operational or stop, as the hardware section's safe_exit says; the other
// devices disabled) or the time limit.
//
// A boot that does not complete is followed by the same safe exit as a run (every device that was
// started, booted or enabled is stopped): describeBootFailure says which device failed and why
// (the drivers' text: an SDO abort with its code, its CiA 301 meaning, the object and the node),
// describeSafeExit what was done to the devices.
//
// Both run through runDeviceCycles (device_cycles.hpp): the next cycle time comes from `next` when
// given (a paced program waits for its deadline there), else it is now + period. Not real time
// (called outside the cycle).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "loop/controller.hpp"
#include "loop/device_cycles.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"

namespace mrqp::loop {

/// The boot ended because a device's boot failed (fault::kBootFailed among its flags).
inline bool bootFailed(const LifecycleResult& boot) noexcept {
  return !boot.done && (boot.flags & drivers::fault::kBootFailed) != 0u;
}

/// Boots and enables every device of `controller`; `now` is advanced cycle by cycle. Ends early
/// when a device's boot has failed or `stop` says so (a signal).
LifecycleResult bootDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig = nullptr, double timeout_s = 10.0,
                            const NextCycleTime& next = NextCycleTime(),
                            const std::function<bool()>& stop = std::function<bool()>());

/// The safe exit of every device of `controller` (see the top of this file).
LifecycleResult exitDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig = nullptr, double timeout_s = 2.0,
                            const NextCycleTime& next = NextCycleTime());

/// Why a boot did not complete, one line per device that reports a fault or is not ready:
/// "ENTITY.JOINT: the drivers' text" (node, SDO abort code, its meaning, object), or the CiA 402
/// state a drive was left in. Call it before exitDevices (the exit rewrites the fault reports).
/// Allocates.
std::vector<std::string> describeBootFailure(const Controller& controller);

/// What the safe exit did to the devices of `hw` ("the arm drives: quick stop, then NMT stop: done
/// after 12 cycles; the other devices disabled"). Allocates.
std::string describeSafeExit(const ResolvedHardware& hw, const LifecycleResult& exit);

}  // namespace mrqp::loop
