// The devices' boot and safe exit (see device_lifecycle.hpp).
#include "loop/device_lifecycle.hpp"

#include <mrqp/firmware_if/cia402.h>
#include <mrqp/drivers/arm_driver.hpp>

namespace mrqp::loop {

namespace fault = drivers::fault;

namespace {

/// "ENTITY.JOINT" / "ENTITY.FRAME" of index i of device d, else the robot's name.
std::string deviceName(const RobotIo& r, const drivers::Device* d, std::size_t i) {
  for (const JointIo& j : r.joints) {
    if (j.device == d && j.index == i) return j.name;
  }
  for (const std::vector<SensorIo>* list : {&r.ft_sensors, &r.imus}) {
    for (const SensorIo& s : *list) {
      if (s.device == d && s.index == i) return s.name;
    }
  }
  return r.name + " (" + d->kind() + " device " + std::to_string(i) + ")";
}

}  // namespace

LifecycleResult bootDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig, double timeout_s, const NextCycleTime& next,
                            const std::function<bool()>& stop) {
  controller.startDevices(now);
  LifecycleResult res = runDeviceCycles(
      now, period, timeout_s, next, [&](drivers::TimeNs t) { return controller.bootCycle(t); },
      [&](drivers::TimeNs t) {
        if (rig != nullptr) rig->advanceTo(t + period);
      },
      [&] { return (controller.bootFlags() & fault::kBootFailed) != 0u || (stop && stop()); });
  res.flags = controller.bootFlags();
  return res;
}

LifecycleResult exitDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig, double timeout_s, const NextCycleTime& next) {
  controller.requestSafeExit(now);
  LifecycleResult res = runDeviceCycles(
      now, period, timeout_s, next, [&](drivers::TimeNs t) { return controller.exitCycle(t); },
      [&](drivers::TimeNs t) {
        if (rig != nullptr) rig->advanceTo(t + period);
      },
      [] { return false; });
  res.flags = controller.exitFlags();
  return res;
}

std::vector<std::string> describeBootFailure(const Controller& controller) {
  std::vector<std::string> lines;
  const bool boot_failed = (controller.bootFlags() & fault::kBootFailed) != 0u;
  for (const RobotIo& r : controller.robots()) {
    for (const auto& dev : r.devices) {
      const drivers::Device* d = dev.get();
      const drivers::FaultReport& rep = d->faults();
      std::vector<bool> told(rep.device_count, false);
      bool any = false;
      for (std::size_t i = 0; i < rep.device_count; ++i) {
        if ((rep.devices[i].flags & ~fault::kSetpointLimited) == 0u) continue;
        lines.push_back(deviceName(r, d, i) + ": " + drivers::describeDeviceFaults(rep.devices[i]));
        told[i] = true;
        any = true;
      }
      for (std::size_t b = 0; b < rep.bus_count; ++b) {
        if (rep.buses[b].flags == 0u) continue;
        Controller::FaultEvent e;
        e.is_bus = true;
        e.bus_faults = rep.buses[b];
        lines.push_back(r.name + ", bus " + std::to_string(b) + " of its " + d->kind() +
                        " device: " + Controller::describe(e));
        any = true;
      }
      if (d->ready()) continue;
      const auto* arm = dynamic_cast<const drivers::ArmDriver*>(d);
      if (arm == nullptr) {
        if (!any) lines.push_back(r.name + ": its " + std::string(d->kind()) + " device is not ready");
        continue;
      }
      if (arm->phase() != drivers::ArmPhase::Running || boot_failed) {
        // Not started, or stopped waiting by another device's failed boot: one line.
        if (!any) {
          lines.push_back(r.name + ": its " + std::to_string(arm->driveCount()) +
                          " CiA 402 drives in phase " + drivers::armPhaseStr(arm->phase()) + ", not enabled");
        }
        continue;
      }
      for (std::size_t i = 0; i < arm->driveCount(); ++i) {
        const drivers::ArmDriveState& s = arm->drive(i);
        if (i < told.size() && told[i]) continue;
        if (s.state == MRQP_FW_CIA402_OPERATION_ENABLED) continue;
        lines.push_back(deviceName(r, d, i) + ": not enabled (CiA 402 state " +
                        mrqp_fw_cia402_state_str(s.state) + ")");
      }
    }
  }
  if (lines.empty()) lines.emplace_back("no device reported a fault");
  return lines;
}

std::string describeSafeExit(const ResolvedHardware& hw, const LifecycleResult& exit) {
  const char* stop = hw.safe_exit.stop == ExitStopKind::DisableVoltage ? "disable voltage" : "quick stop";
  const char* nmt = hw.safe_exit.nmt == ExitNmtKind::Stopped     ? "NMT stop"
                    : hw.safe_exit.nmt == ExitNmtKind::Unchanged ? "NMT state unchanged"
                                                                 : "NMT pre-operational";
  std::string text = std::string("safe exit of every device (CiA 402 drives: ") + stop + ", then " + nmt +
                     "; the other devices disabled): " + (exit.done ? "done" : "NOT completed") + " after " +
                     std::to_string(exit.cycles) + " cycles";
  if (exit.flags != 0u) text += " (flags seen: " + drivers::faultFlagsStr(exit.flags) + ")";
  return text;
}

}  // namespace mrqp::loop
