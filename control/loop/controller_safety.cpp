// The controller's safety through the drivers (docs/loop.md, "Safety"): the fault events the
// drivers report (copied in the cycle, described outside it with the drivers' own text), the safe
// state handed to the arm drivers (ArmDriver::setSafeState, and the CiA 402 quick stop for
// quick_stop robots) in the cycle that trips, the loop's recovery of recoverable drive faults under
// the hardware section's `recovery:` policy, and the safe exit after the last cycle
// (ArmDriver::requestSafeExit; the other devices disabled).
//
// Recoverable: a fault of a CiA 402 drive that is only about communication — its heartbeat lost,
// an NMT state other than operational or a reboot (state mismatch), feedback missing, a recovery
// under way, an EMCY of the communication classes (0x81xx, 0x82xx) and the power-stage fault such
// an EMCY caused. While the policy recovers, every robot holds with damping, the QP is not solved,
// and each attempt asks the arm drivers for a recovery (ArmDriver::requestRecovery: reconfigure a
// rebooted drive, NMT start, fault reset and enable); the loop resumes when every device is ready
// and reports no fatal flag, and stops (driver fault) when `max_attempts` attempts of `backoff`
// seconds each have not brought them back. A safe stop the controller decided is never recovered.
#include <mrqp/drivers/arm_driver.hpp>

#include <algorithm>

#include "loop/controller.hpp"

namespace mrqp::loop {

namespace fault = drivers::fault;

namespace {

constexpr std::uint32_t kCommunicationFlags =
    fault::kHeartbeatLost | fault::kStateMismatch | fault::kFeedbackMissing | fault::kRecovering;

bool communicationEmcy(std::uint16_t code) noexcept {
  const std::uint16_t cls = static_cast<std::uint16_t>(code & 0xFF00u);
  return cls == 0x8100u || cls == 0x8200u;
}

/// The flags of one device that a recovery may clear.
std::uint32_t recoverableFlags(const drivers::DeviceFaults& d) noexcept {
  std::uint32_t ok = kCommunicationFlags;
  if (communicationEmcy(d.emcy_code)) ok |= fault::kEmcy | fault::kDeviceFault;
  return d.flags & ok;
}

}  // namespace

void Controller::initSafety(const ResolvedHardware& hw) {
  recovery_ = hw.recovery;
  for (const ResolvedBus& b : hw.buses) bus_names_.push_back(b.decl.name);
  std::size_t offset = 0;
  for (RobotIo& r : robots_) {
    for (auto& d : r.devices) {
      if (auto* arm = dynamic_cast<drivers::ArmDriver*>(d.get())) arms_.push_back(arm);
      const drivers::FaultReport& rep = d->faults();
      reported_slots_.push_back(ReportedSlot{d.get(), offset, rep.device_count, rep.bus_count});
      offset += rep.device_count + rep.bus_count;
    }
  }
  reported_.assign(offset, 0u);
}

const std::string* Controller::deviceName(const RobotIo& r, const drivers::Device* d,
                                          std::size_t i) const noexcept {
  for (const JointIo& j : r.joints) {
    if (j.device == d && j.index == i) return &j.name;
  }
  for (const SensorIo& s : r.ft_sensors) {
    if (s.device == d && s.index == i) return &s.name;
  }
  for (const SensorIo& s : r.imus) {
    if (s.device == d && s.index == i) return &s.name;
  }
  return &r.name;
}

const std::string* Controller::busName(const RobotIo& r, std::size_t b) const noexcept {
  if (b < r.routers.size()) {
    for (std::size_t k = 0; k < routers_.size(); ++k) {
      if (routers_[k].get() == r.routers[b]) return &bus_names_[k];
    }
  }
  return &r.name;
}

void Controller::recordEvents(const RobotIo& r, const drivers::Device& d, const drivers::FaultReport& rep,
                              drivers::TimeNs now) noexcept {
  const ReportedSlot* slot = nullptr;
  for (const ReportedSlot& s : reported_slots_) {
    if (s.device == &d) slot = &s;
  }
  if (slot == nullptr) return;
  auto add = [&](std::uint32_t* seen, std::uint32_t flags) -> FaultEvent* {
    const std::uint32_t fresh = flags & ~*seen & ~fault::kSetpointLimited;
    if (fresh == 0u) return nullptr;
    *seen |= fresh;
    if (event_count_ >= events_.size()) {
      ++events_dropped_;
      return nullptr;
    }
    FaultEvent& e = events_[event_count_++];
    e = FaultEvent{};
    e.t = now - start_;
    e.cycle = cycle_;
    return &e;
  };
  for (std::size_t i = 0; i < rep.device_count && i < slot->devices; ++i) {
    if (FaultEvent* e = add(&reported_[slot->offset + i], rep.devices[i].flags)) {
      e->where = deviceName(r, &d, i);
      e->device = rep.devices[i];
    }
  }
  for (std::size_t b = 0; b < rep.bus_count && b < slot->buses; ++b) {
    if (FaultEvent* e = add(&reported_[slot->offset + slot->devices + b], rep.buses[b].flags)) {
      e->where = busName(r, b);
      e->is_bus = true;
      e->bus_faults = rep.buses[b];
    }
  }
}

void Controller::onDeviceFaults(RobotIo& r, drivers::Device& d, const drivers::FaultReport& rep,
                                std::uint32_t flags, drivers::TimeNs now) noexcept {
  recordEvents(r, d, rep, now);
  if ((flags & fatal_) == 0u) return;
  // The first device (else bus) with a fatal flag names the fault; is every fatal flag one a
  // recovery may clear?
  FaultEvent what;
  what.t = now - start_;
  what.cycle = cycle_;
  what.where = &r.name;
  bool named = false;
  bool recoverable = recovery_.max_attempts > 0 && stop_ == StopReason::None && isArm(&d);
  for (std::size_t i = 0; i < rep.device_count; ++i) {
    const drivers::DeviceFaults& df = rep.devices[i];
    if ((df.flags & fatal_) == 0u) continue;
    recoverable = recoverable && (df.flags & fatal_ & ~recoverableFlags(df)) == 0u;
    if (!named) {
      named = true;
      what.where = deviceName(r, &d, i);
      what.device = df;
    }
  }
  for (std::size_t b = 0; b < rep.bus_count; ++b) {
    const bool off = (rep.buses[b].error_flags & drivers::bus_error::kBusOff) != 0u;
    if ((rep.buses[b].flags & fatal_) == 0u && !off) continue;
    recoverable = false;
    if (!named) {
      named = true;
      what.where = busName(r, b);
      what.is_bus = true;
      what.bus_faults = rep.buses[b];
    }
  }
  if (recoverable) {
    if (!recovering_) startLoopRecovery(what, flags & fatal_, now);
    return;
  }
  if (stop_ == StopReason::None) {
    stop_event_ = what;
    stop_event_set_ = true;
  }
  trip(StopReason::DriverFault, flags & fatal_, what.where, now);
}

bool Controller::isArm(const drivers::Device* d) const noexcept {
  return std::any_of(arms_.begin(), arms_.end(), [d](const drivers::ArmDriver* a) { return a == d; });
}

void Controller::startLoopRecovery(const FaultEvent& what, std::uint32_t flags,
                                   drivers::TimeNs now) noexcept {
  recovering_ = true;
  recovery_event_ = what;
  recovery_flags_ = flags;
  recovery_attempts_ = 1;
  recovery_next_ = now + static_cast<drivers::TimeNs>(recovery_.backoff_s * 1e9);
  for (drivers::ArmDriver* a : arms_) (void)a->requestRecovery(now);
}

void Controller::stepLoopRecovery(drivers::TimeNs now) noexcept {
  if (!recovering_) return;
  if (stop_ != StopReason::None) {
    recovering_ = false;
    return;
  }
  bool clean = true;
  for (RobotIo& r : robots_) {
    for (auto& d : r.devices) clean = clean && d->ready() && (d->faults().flags & fatal_) == 0u;
  }
  if (clean) {
    recovering_ = false;
    ++recoveries_;
    for (RobotIo& r : robots_) {
      std::fill(r.stale.begin(), r.stale.end(), 0u);
      std::fill(r.miss_rate.begin(), r.miss_rate.end(), 0.0);
      for (SensorIo& s : r.ft_sensors) s.stale = 0;
      for (SensorIo& s : r.imus) s.stale = 0;
    }
    return;
  }
  if (now < recovery_next_) return;
  if (recovery_attempts_ >= recovery_.max_attempts) {
    stop_event_ = recovery_event_;
    stop_event_set_ = true;
    trip(StopReason::DriverFault, recovery_flags_, recovery_event_.where, now);
    return;
  }
  ++recovery_attempts_;
  recovery_next_ = now + static_cast<drivers::TimeNs>(recovery_.backoff_s * 1e9);
  for (drivers::ArmDriver* a : arms_) (void)a->requestRecovery(now);
}

void Controller::staleJoint(RobotIo& r, std::size_t joint, std::uint32_t flag, drivers::TimeNs now) noexcept {
  const JointIo& j = r.joints[joint];
  if (recovery_.max_attempts > 0 && stop_ == StopReason::None && isArm(j.device)) {
    if (recovering_) return;
    FaultEvent what;
    what.t = now - start_;
    what.cycle = cycle_;
    what.where = &j.name;
    const drivers::FaultReport& rep = j.device->faults();
    if (j.index < rep.device_count) what.device = rep.devices[j.index];
    what.device.flags |= flag;
    startLoopRecovery(what, flag, now);
    return;
  }
  trip(StopReason::StaleSensor, flag, &j.name, now);
}

void Controller::enterSafeState(drivers::TimeNs now) noexcept {
  recovering_ = false;
  // No recovery from now on, by the driver or the loop; quick_stop robots' devices get the CiA 402
  // quick stop (MIT motors: damping only; hand boards: HOLD) with this cycle's frames.
  for (drivers::ArmDriver* a : arms_) a->setSafeState(true);
  for (RobotIo& r : robots_) {
    if (r.safe_stop != SafeStop::QuickStop) continue;
    for (auto& d : r.devices) d->requestQuickStop(now);
  }
}

void Controller::requestSafeExit(drivers::TimeNs now) noexcept {
  exiting_ = true;
  exit_cycle_ = 0;
  recovering_ = false;
  for (RobotIo& r : robots_) {
    for (auto& d : r.devices) {
      if (isArm(d.get())) {
        auto* arm = static_cast<drivers::ArmDriver*>(d.get());
        arm->setSafeState(true);
        arm->requestSafeExit(now);
      } else {
        d->requestDisable(now);
      }
    }
  }
}

bool Controller::exitCycle(drivers::TimeNs now) noexcept {
  int longest = 1;
  for (RobotIo& r : robots_) {
    longest = std::max(longest, r.divisor);
    if (exit_cycle_ % static_cast<std::uint64_t>(r.divisor) != 0u) continue;
    for (drivers::BusRouter* router : r.routers) router->poll(now);
    for (auto& d : r.devices) exit_flags_ |= d->update(now).flags;
    for (auto& d : r.devices) d->transmit(now);
  }
  ++exit_cycle_;
  // Every arm driver stopped its drives; the others' disable went out for three robot cycles.
  const bool arms_done =
      std::all_of(arms_.begin(), arms_.end(), [](const drivers::ArmDriver* a) { return a->safeExitDone(); });
  return arms_done && exit_cycle_ >= static_cast<std::uint64_t>(3 * longest);
}

bool Controller::exitDone() const noexcept {
  return exiting_ && std::all_of(arms_.begin(), arms_.end(),
                                 [](const drivers::ArmDriver* a) { return a->safeExitDone(); });
}

std::string Controller::describe(const FaultEvent& e) {
  if (!e.is_bus) return drivers::describeDeviceFaults(e.device);
  // The drivers' text of a bus line ("bus N: flags (state, TEC, REC)") without its index.
  drivers::FaultReport one;
  one.buses = &e.bus_faults;
  one.bus_count = 1;
  std::string text = drivers::describeFaults(one, "device");
  const std::size_t colon = text.find(": ");
  if (colon != std::string::npos) text.erase(0, colon + 2);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string Controller::stopDescription() const {
  if (!stop_event_set_) return std::string();
  return *stop_event_.where + ": " + describe(stop_event_);
}

}  // namespace mrqp::loop
