// mrqp drivers -- arm drives, CiA 402 master: recovery of a drive that left Operational, rebooted
// or fell into Fault, and the safe exit (stop, then NMT pre-operational / stopped). The real-time
// part; see arm_driver.hpp and docs/drivers.md ("Bringing up a vendor's drive").
#include "cia402_states.hpp"
#include "driver_util.hpp"
#include "mrqp/drivers/arm_driver.hpp"
#include "mrqp/firmware_if/nmt.h"
#include "mrqp/firmware_if/objects.h"
#include "mrqp/firmware_if/sdo.h"

namespace mrqp::drivers {

using detail::cia402FaultState;
using detail::cia402StateReached;

bool ArmDriver::needsRecovery(std::size_t i) const noexcept {
  if (i >= drives_.size() || phase_ != ArmPhase::Running) {
    return false;
  }
  const Drive& d = drives_[i];
  if (d.recovery != Drive::Recovery::None) {
    return false;
  }
  const bool left_operational = d.heartbeat.monitoring() &&
                                d.state.nmt_state != MRQP_FW_NMT_STATE_OPERATIONAL &&
                                d.heartbeat.last() > d.nmt.commanded() + 2 * config_.cycle_period;
  const bool fell =
      wanted_ == MRQP_FW_CIA402_OPERATION_ENABLED && d.state.valid && cia402FaultState(d.state.state);
  return d.rebooted || left_operational || fell;
}

bool ArmDriver::ready() const noexcept {
  if (phase_ != ArmPhase::Running || !allEnabled()) {
    return false;
  }
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    if (needsRecovery(i) || recovering(i)) {
      return false;
    }
  }
  return true;
}

bool ArmDriver::recovering(std::size_t i) const noexcept {
  return i < drives_.size() && drives_[i].recovery != Drive::Recovery::None;
}

std::size_t ArmDriver::requestRecovery(TimeNs now) noexcept {
  if (safe_state_ || phase_ != ArmPhase::Running) {
    return 0;
  }
  std::size_t started = 0;
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    if (needsRecovery(i)) {
      startRecovery(drives_[i], now);
      ++started;
    }
  }
  return started;
}

void ArmDriver::startRecovery(Drive& d, TimeNs now) noexcept {
  d.recovery_failed = false;
  d.attempted = true;
  d.recovery_attempt = now;
  d.recovery_since = now;
  d.sp_position_valid = false;
  d.sp_torque_valid = false;
  if (d.rebooted) {
    // The drive lost its configuration: write it again (no reset: it has just booted), then start.
    d.rebooted = false;
    d.has_pending = false;
    d.sdo.restart();
    d.heartbeat.restart();
    d.state.valid = false;
    d.target = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
    d.recovery = Drive::Recovery::Configuring;
    return;
  }
  if (d.state.nmt_state != MRQP_FW_NMT_STATE_OPERATIONAL && d.heartbeat.monitoring()) {
    mrqp_fw_frame f;
    d.nmt.startRemote(now, &f);
    setPending(d, f);
  }
  d.recovery = Drive::Recovery::Starting;
}

void ArmDriver::stepRecovery(Drive& d, TimeNs now) noexcept {
  if (d.recovery == Drive::Recovery::None) {
    return;
  }
  if (now - d.recovery_since > config_.boot_timeout) {
    d.events |= fault::kTimeout;
    failBoot(d, fault::kBootFailed);  // in a recovery: only this drive stays down
    return;
  }
  if (d.recovery == Drive::Recovery::Configuring) {
    mrqp_fw_frame out;
    const SdoWriteSequence::Step step = d.sdo.process(now, false, &out);
    if (failedSdoStep(d, step, out)) {
      return;
    }
    if (d.sdo.done() && !d.has_pending) {
      d.faults.tolerated_aborts = d.sdo.tolerated();
      mrqp_fw_frame f;
      d.nmt.startRemote(now, &f);
      setPending(d, f);
      d.recovery = Drive::Recovery::Starting;
    }
    return;
  }
  // Starting: operational again (heard in its heartbeat, or its PDOs when it sends none), then the
  // CiA 402 part towards what the caller last asked for -- unless the safe state is in force. A
  // heartbeat heard two cycles after the start that is not operational: the start did not hold
  // (the drive fell again) or that heartbeat left the drive before the start reached it (a late
  // bus): the start is sent again, within this recovery's boot timeout; in the safe state the
  // recovery ends there instead.
  if (d.heartbeat.monitoring() && d.state.nmt_state != MRQP_FW_NMT_STATE_OPERATIONAL &&
      d.heartbeat.last() > d.nmt.commanded() + 2 * config_.cycle_period && !d.has_pending) {
    if (safe_state_) {
      d.recovery = Drive::Recovery::None;
      return;
    }
    mrqp_fw_frame f;
    d.nmt.startRemote(now, &f);
    setPending(d, f);
    return;
  }
  const bool operational = d.heartbeat.monitoring() ? d.state.nmt_state == MRQP_FW_NMT_STATE_OPERATIONAL &&
                                                          d.heartbeat.last() > d.nmt.commanded()
                                                    : d.state.valid;
  if (d.has_pending || !operational || !d.state.valid) {
    return;
  }
  if (safe_state_) {
    d.recovery = Drive::Recovery::None;  // back on the bus, but not enabled
    return;
  }
  if (d.target != wanted_) {
    d.target = wanted_;
    d.target_since = now;
  }
  if (cia402StateReached(wanted_, d.state.state)) {
    d.recovery = Drive::Recovery::None;
    ++d.faults.recoveries;
  }
}

void ArmDriver::transmitRecovery(Drive& d, std::size_t* count, TimeNs now) noexcept {
  if (d.recovery != Drive::Recovery::Configuring || d.sdo.done() || d.sdo.busy() || d.has_pending) {
    return;
  }
  mrqp_fw_frame out;
  if (d.sdo.process(now, true, &out) != SdoWriteSequence::Step::Send) {
    failBoot(d, fault::kBootFailed);
    return;
  }
  if (send(d.cfg.bus, &d, out)) {
    ++*count;
  } else {
    setPending(d, out);
  }
}

void ArmDriver::requestSafeExit(TimeNs now) noexcept {
  if (phase_ == ArmPhase::Stopping || phase_ == ArmPhase::Stopped) {
    return;
  }
  if (phase_ == ArmPhase::Idle) {
    phase_ = ArmPhase::Stopped;  // never started: nothing on the bus to stop
    phase_since_ = now;
    return;
  }
  const bool running = phase_ == ArmPhase::Running;
  phase_ = ArmPhase::Stopping;
  phase_since_ = now;
  exit_since_ = now;
  exit_nmt_stage_ = false;
  const mrqp_fw_cia402_state stop = config_.exit_stop == ExitStop::QuickStop
                                        ? MRQP_FW_CIA402_QUICK_STOP_ACTIVE
                                        : MRQP_FW_CIA402_SWITCH_ON_DISABLED;
  for (Drive& d : drives_) {
    d.recovery = Drive::Recovery::None;
    d.exit_step = 0;
    d.target = stop;
    d.target_since = now;
    d.sp_position_valid = false;
    d.sp_torque_valid = false;
    if (!running) {
      d.has_pending = false;  // a boot under way is abandoned
      d.sdo.restart();
    }
  }
  if (!running) {
    exit_since_ = now - config_.exit_timeout - 1;  // no PDOs to wait for: straight to NMT
  }
}

void ArmDriver::stepSafeExit(TimeNs now) noexcept {
  if (exit_nmt_stage_) {
    return;  // the NMT commands are queued (transmit() ends the exit)
  }
  bool all = true;
  for (const Drive& d : drives_) {
    // A drive without feedback, or not operational, cannot report a stop, and a drive in Fault has
    // its power stage off already: nothing to wait for.
    const bool talking = d.state.valid && d.state.nmt_state != MRQP_FW_NMT_STATE_PRE_OPERATIONAL &&
                         d.state.nmt_state != MRQP_FW_NMT_STATE_STOPPED && !cia402FaultState(d.state.state);
    if (talking && !cia402StateReached(d.target, d.state.state)) {
      all = false;
    }
  }
  const bool timed_out = now - exit_since_ > config_.exit_timeout;
  if (all && !timed_out) {
    // Quick stop reached (or the drive already went on to Switch on disabled): disable voltage.
    bool more = false;
    for (Drive& d : drives_) {
      if (d.target == MRQP_FW_CIA402_QUICK_STOP_ACTIVE) {
        d.target = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
        d.target_since = now;
        more = true;
      }
    }
    if (more) {
      return;  // one more round: Switch on disabled
    }
  }
  if (!all && !timed_out) {
    return;
  }
  // Power stage stopped (or timed out): a drive whose PDOs are stopped (not Operational) but was
  // last seen with its power stage on gets disable voltage through SDO (0x6040 = 0x0000), then
  // every drive its NMT command (transmit() queues it after the SDO write and ends the exit).
  exit_nmt_stage_ = true;
  for (Drive& d : drives_) {
    const bool operational = d.state.nmt_state == MRQP_FW_NMT_STATE_OPERATIONAL;
    const bool powered =
        d.state.valid && !cia402StateReached(MRQP_FW_CIA402_SWITCH_ON_DISABLED, d.state.state);
    if (!operational && powered) {
      const std::uint8_t zero[2] = {0, 0};
      mrqp_fw_frame f;
      (void)mrqp_fw_sdo_pack_download_req(d.cfg.node, MRQP_FW_OBJ_CONTROLWORD, 0, zero, 2, &f);
      setPending(d, f);
      d.exit_step = 1;
    } else {
      queueExitNmt(d);
    }
  }
}

void ArmDriver::queueExitNmt(Drive& d) noexcept {
  if (config_.exit_nmt == ExitNmt::Unchanged) {
    d.exit_step = 3;
    return;
  }
  mrqp_fw_frame f;
  (void)mrqp_fw_nmt_pack(config_.exit_nmt == ExitNmt::Stopped ? MRQP_FW_NMT_STOP : MRQP_FW_NMT_ENTER_PREOP,
                         d.cfg.node, &f);
  setPending(d, f);
  d.exit_step = 2;
}

}  // namespace mrqp::drivers
