// mrqp drivers -- arm drives, CiA 402 master: the real-time part. See
// arm_driver.hpp.
#include "mrqp/drivers/arm_driver.hpp"

#include "cia402_states.hpp"
#include "driver_util.hpp"
#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/emcy.h"
#include "mrqp/firmware_if/nmt.h"

namespace mrqp::drivers {

using detail::cia402FaultState;
using detail::cia402StateReached;

const char* armPhaseStr(ArmPhase phase) noexcept {
  switch (phase) {
    case ArmPhase::Idle:
      return "idle";
    case ArmPhase::Resetting:
      return "resetting";
    case ArmPhase::Configuring:
      return "configuring";
    case ArmPhase::Starting:
      return "starting";
    case ArmPhase::Running:
      return "running";
    case ArmPhase::Failed:
      return "failed";
    case ArmPhase::Stopping:
      return "stopping";
    case ArmPhase::Stopped:
      return "stopped";
  }
  return "unknown";
}

bool ArmDriver::send(std::size_t slot, Drive* d, const mrqp_fw_frame& f) noexcept {
  const SendResult r = routers_.router(slot).bus().send(f);
  if (r == SendResult::Ok) {
    return true;
  }
  if (r == SendResult::QueueFull && d != nullptr) {
    ++d->faults.tx_queue_full;
    d->events |= fault::kTxQueueFull;
  }
  return false;
}

void ArmDriver::setPending(Drive& d, const mrqp_fw_frame& f) noexcept {
  d.pending = f;
  d.has_pending = true;
}

bool ArmDriver::failedSdoStep(Drive& d, SdoWriteSequence::Step step, const mrqp_fw_frame& out) noexcept {
  if (step != SdoWriteSequence::Step::Failed && step != SdoWriteSequence::Step::FailedSend) {
    return false;
  }
  if (step == SdoWriteSequence::Step::FailedSend) {
    setPending(d, out);
  }
  d.faults.sdo_abort_code = d.sdo.abortCode();
  d.faults.sdo_index = d.sdo.current().index;
  d.faults.sdo_subindex = d.sdo.current().subindex;
  failBoot(d, fault::kTimeout | fault::kBootFailed);
  return true;
}

void ArmDriver::failBoot(Drive& d, std::uint32_t flags) noexcept {
  d.events |= flags;
  if (d.recovery != Drive::Recovery::None) {
    // A recovery's reconfiguration failed: this drive stays down, the others
    // run on.
    d.recovery = Drive::Recovery::None;
    d.recovery_failed = true;
    return;
  }
  d.sticky |= flags;
  phase_ = ArmPhase::Failed;
}

void ArmDriver::start(TimeNs now) noexcept {
  phase_ = config_.reset == NmtReset::None ? ArmPhase::Configuring : ArmPhase::Resetting;
  phase_since_ = now;
  master_heartbeat_.restart(now);
  exit_nmt_stage_ = false;
  for (BusSlot& b : buses_) {
    b.cyclic_sent = false;
    b.sync.restart();
    b.jitter.restart();
  }
  for (Drive& d : drives_) {
    d.sdo.restart();
    d.has_pending = false;
    d.heartbeat.restart();
    d.sticky = 0;
    d.faults.sdo_abort_code = 0;
    d.faults.sdo_index = 0;
    d.faults.sdo_subindex = 0;
    d.faults.sdo_check_failed = false;
    d.faults.tolerated_aborts = 0;
    d.faults.missed_cycles = 0;
    d.recovery = Drive::Recovery::None;
    d.rebooted = false;
    d.recovery_failed = false;
    d.attempted = false;
    d.exit_step = 0;
    d.target = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
    d.target_since = now;
    d.sp_position_valid = false;
    d.sp_torque_valid = false;
    d.got_tpdo1 = false;
    d.state.valid = false;
    d.state.state = MRQP_FW_CIA402_UNKNOWN;
    d.state.controlword = 0;
    mrqp_fw_frame f;
    d.nmt.begin(now, &f);
    setPending(d, f);
  }
}

void ArmDriver::setTarget(mrqp_fw_cia402_state target, TimeNs now) noexcept {
  if (phase_ == ArmPhase::Stopping || phase_ == ArmPhase::Stopped) {
    return;  // the safe exit owns the drives now
  }
  wanted_ = target;
  for (Drive& d : drives_) {
    d.target = target;
    d.target_since = now;
    d.sp_position_valid = false;
    d.sp_torque_valid = false;
  }
}

void ArmDriver::requestEnable(TimeNs now) noexcept { setTarget(MRQP_FW_CIA402_OPERATION_ENABLED, now); }

void ArmDriver::requestDisable(TimeNs now) noexcept { setTarget(MRQP_FW_CIA402_SWITCH_ON_DISABLED, now); }

void ArmDriver::requestQuickStop(TimeNs now) noexcept { setTarget(MRQP_FW_CIA402_QUICK_STOP_ACTIVE, now); }

bool ArmDriver::allEnabled() const noexcept {
  for (const Drive& d : drives_) {
    if (!d.state.valid || d.state.state != MRQP_FW_CIA402_OPERATION_ENABLED) {
      return false;
    }
  }
  return !drives_.empty();
}

bool ArmDriver::allDisabled() const noexcept {
  for (const Drive& d : drives_) {
    if (!d.state.valid || !cia402StateReached(MRQP_FW_CIA402_SWITCH_ON_DISABLED, d.state.state)) {
      return false;
    }
  }
  return !drives_.empty();
}

SetpointResult ArmDriver::setPosition(std::size_t i, double rad) noexcept {
  if (i >= drives_.size()) {
    return SetpointResult::BadIndex;
  }
  Drive& d = drives_[i];
  if (!detail::finite(rad)) {
    ++d.faults.refused_setpoints;
    d.events |= fault::kSetpointRefused;
    return SetpointResult::Refused;
  }
  bool limited = false;
  d.sp_position = detail::clamp(rad, d.cfg.position_min, d.cfg.position_max, &limited);
  d.sp_position_valid = true;
  if (limited) {
    ++d.faults.limited_setpoints;
    d.events |= fault::kSetpointLimited;
    return SetpointResult::Limited;
  }
  return SetpointResult::Ok;
}

SetpointResult ArmDriver::setTorque(std::size_t i, double nm) noexcept {
  if (i >= drives_.size()) {
    return SetpointResult::BadIndex;
  }
  Drive& d = drives_[i];
  if (!detail::finite(nm)) {
    ++d.faults.refused_setpoints;
    d.events |= fault::kSetpointRefused;
    return SetpointResult::Refused;
  }
  bool limited = false;
  d.sp_torque = detail::clamp(nm, -d.cfg.torque_limit, d.cfg.torque_limit, &limited);
  d.sp_torque_valid = true;
  if (limited) {
    ++d.faults.limited_setpoints;
    d.events |= fault::kSetpointLimited;
    return SetpointResult::Limited;
  }
  return SetpointResult::Ok;
}

JointMode ArmDriver::jointMode(std::size_t i) const noexcept {
  return i < drives_.size() && drives_[i].cfg.mode == MRQP_FW_MODE_CST ? JointMode::Torque
                                                                       : JointMode::Position;
}

SetpointResult ArmDriver::setJoint(std::size_t i, const JointCommand& c) noexcept {
  if (i >= drives_.size()) {
    return SetpointResult::BadIndex;
  }
  if (drives_[i].cfg.mode == MRQP_FW_MODE_CST) {
    return setTorque(i, c.torque);
  }
  // CSP: target position and torque feed-forward; the worse of the two results.
  const SetpointResult p = setPosition(i, c.position);
  const SetpointResult t = setTorque(i, c.torque);
  return static_cast<std::uint8_t>(p) >= static_cast<std::uint8_t>(t) ? p : t;
}

JointFeedback ArmDriver::joint(std::size_t i) const noexcept {
  JointFeedback out;
  if (i >= drives_.size()) {
    return out;
  }
  const ArmDriveState& s = drives_[i].state;
  out.position = s.position;
  out.velocity = s.velocity;
  out.torque = s.torque;
  out.valid = s.valid;
  out.fresh = s.fresh;
  out.timestamp = s.timestamp;
  return out;
}

const FaultReport& ArmDriver::update(TimeNs now) noexcept {
  routers_.startCycle();

  // Boot progression.
  if (phase_ == ArmPhase::Resetting) {
    bool all = true;
    for (const Drive& d : drives_) {
      all = all && d.nmt.booted();
    }
    if (all) {
      phase_ = ArmPhase::Configuring;
      phase_since_ = now;
    } else {
      for (Drive& d : drives_) {
        if (d.nmt.process(now)) {
          failBoot(d, fault::kTimeout | fault::kBootFailed);
        }
      }
    }
  }
  if (phase_ == ArmPhase::Configuring) {
    bool all = true;
    for (Drive& d : drives_) {
      mrqp_fw_frame out;
      const SdoWriteSequence::Step step = d.sdo.process(now, false, &out);
      failedSdoStep(d, step, out);
      d.faults.tolerated_aborts = d.sdo.tolerated();
      all = all && d.sdo.done();
    }
    if (phase_ == ArmPhase::Configuring && all) {
      phase_ = ArmPhase::Starting;
      phase_since_ = now;
      for (Drive& d : drives_) {
        mrqp_fw_frame f;
        d.nmt.startRemote(now, &f);
        setPending(d, f);
      }
    }
  }

  if (phase_ == ArmPhase::Running) {
    for (Drive& d : drives_) {
      stepRecovery(d, now);
    }
  }
  if (phase_ == ArmPhase::Stopping) {
    stepSafeExit(now);
  }

  const TimeNs nmt_grace = 2 * config_.cycle_period;
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    const BusSlot& slot = buses_[d.cfg.bus];
    std::uint32_t flags = d.events | d.sticky;
    d.events = 0;
    if (d.recovery != Drive::Recovery::None) {
      flags |= fault::kRecovering;
    }
    if (d.recovery_failed) {
      flags |= fault::kBootFailed;
    }
    d.state.fresh = d.got_tpdo1;

    if (phase_ == ArmPhase::Running && slot.cyclic_sent) {
      d.faults.missed_cycles = d.got_tpdo1 ? 0u : d.faults.missed_cycles + 1u;
    }
    d.got_tpdo1 = false;
    if (d.faults.missed_cycles >= config_.feedback_missing_cycles) {
      flags |= fault::kFeedbackMissing;
    }
    if (d.heartbeat.process(now)) {
      flags |= fault::kHeartbeatLost;
    }
    if (d.faults.emcy_code != 0u) {
      flags |= fault::kEmcy;
    }
    if (phase_ == ArmPhase::Running) {
      if (d.heartbeat.monitoring() && d.state.nmt_state != MRQP_FW_NMT_STATE_OPERATIONAL &&
          d.heartbeat.last() > d.nmt.commanded() + nmt_grace) {
        flags |= fault::kStateMismatch;
      }
      if (d.state.valid) {
        const mrqp_fw_cia402_state s = d.state.state;
        if (cia402FaultState(s)) {
          flags |= fault::kDeviceFault;
          if (d.target == MRQP_FW_CIA402_OPERATION_ENABLED && !cia402FaultState(d.prev_state)) {
            // Fell into Fault while enabled: stay there until the caller asks
            // again.
            d.target = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
            d.target_since = now;
          }
        }
        if (s != MRQP_FW_CIA402_OPERATION_ENABLED) {
          d.sp_position_valid = false;
          d.sp_torque_valid = false;
        }
        if (config_.tpdo2 && d.tpdo2_seen && s == MRQP_FW_CIA402_OPERATION_ENABLED &&
            d.state.mode_display != d.cfg.mode) {
          flags |= fault::kStateMismatch;
        }
        d.prev_state = s;
      }
      // A recovery has its own time limit (boot_timeout); the target's is measured once it is back.
      if (d.recovery == Drive::Recovery::None &&
          !(d.state.valid && cia402StateReached(d.target, d.state.state)) &&
          now - d.target_since > config_.enable_timeout) {
        flags |= fault::kTimeout;
      }
    }
    d.faults.nmt_state = d.state.nmt_state;
    d.faults.flags = flags;
    routers_.device(i) = d.faults;
  }
  if (phase_ == ArmPhase::Running && config_.recovery == RecoveryPolicy::Automatic && !safe_state_) {
    for (std::size_t i = 0; i < drives_.size(); ++i) {
      Drive& d = drives_[i];
      if (needsRecovery(i) && (!d.attempted || now - d.recovery_attempt >= config_.recovery_retry)) {
        startRecovery(d, now);
      }
    }
  }
  return routers_.publish();
}

std::size_t ArmDriver::transmit(TimeNs now) noexcept {
  std::size_t count = 0;
  // One-shot frames (NMT, SDO) first; kept for the next cycle when the queue is
  // full.
  for (Drive& d : drives_) {
    if (d.has_pending && send(d.cfg.bus, &d, d.pending)) {
      d.has_pending = false;
      ++count;
      if (phase_ == ArmPhase::Resetting) {
        d.nmt.sent(now);  // the reset is on its way (NmtBoot ignores anything else)
      }
      if (d.sdo.busy()) {
        d.sdo.sent(now);
      }
      if (phase_ == ArmPhase::Stopping && exit_nmt_stage_) {
        if (d.exit_step == 1) {
          queueExitNmt(d);  // the SDO disable is on its way: the NMT command next
        } else if (d.exit_step == 2) {
          d.exit_step = 3;  // the NMT command of the safe exit is on its way
        }
      }
    }
  }

  switch (phase_) {
    case ArmPhase::Configuring:
      for (Drive& d : drives_) {
        if (d.sdo.done() || d.sdo.busy() || d.has_pending) {
          continue;
        }
        mrqp_fw_frame out;
        if (d.sdo.process(now, true, &out) != SdoWriteSequence::Step::Send) {
          failBoot(d, fault::kBootFailed);
          continue;
        }
        if (send(d.cfg.bus, &d, out)) {
          ++count;
        } else {
          setPending(d, out);
        }
      }
      break;
    case ArmPhase::Starting: {
      bool all_sent = true;
      for (const Drive& d : drives_) {
        all_sent = all_sent && !d.has_pending;
      }
      if (all_sent) {
        phase_ = ArmPhase::Running;
        phase_since_ = now;
        for (Drive& d : drives_) {
          d.target_since = now;
          d.prev_state = MRQP_FW_CIA402_UNKNOWN;
        }
      }
      break;
    }
    case ArmPhase::Running:
      for (Drive& d : drives_) {
        transmitRecovery(d, &count, now);
      }
      count += transmitCyclic(now);
      break;
    case ArmPhase::Stopping: {
      if (!exit_nmt_stage_) {
        count += transmitCyclic(now);
        break;
      }
      bool all_sent = true;
      for (const Drive& d : drives_) {
        all_sent = all_sent && d.exit_step == 3 && !d.has_pending;
      }
      if (all_sent) {
        phase_ = ArmPhase::Stopped;
        phase_since_ = now;
      }
      break;
    }
    case ArmPhase::Idle:
    case ArmPhase::Resetting:
    case ArmPhase::Failed:
    case ArmPhase::Stopped:
      break;
  }

  mrqp_fw_frame hb;
  if (phase_ != ArmPhase::Idle && master_heartbeat_.process(now, &hb)) {
    for (std::size_t s = 0; s < buses_.size(); ++s) {
      if (buses_[s].has_drives && send(s, nullptr, hb)) {
        ++count;
      }
    }
  }
  return count;
}

std::size_t ArmDriver::transmitCyclic(TimeNs now) noexcept {
  std::size_t count = 0;
  for (std::size_t s = 0; s < buses_.size(); ++s) {
    BusSlot& slot = buses_[s];
    if (!slot.has_drives) {
      continue;
    }
    for (Drive& d : drives_) {
      if (d.cfg.bus != s) {
        continue;
      }
      const mrqp_fw_cia402_state current = d.state.valid ? d.state.state : MRQP_FW_CIA402_UNKNOWN;
      // A drive in Fault is only reset when the caller asks for Operation
      // enabled again.
      const std::uint16_t cw =
          cia402FaultState(current) && d.target != MRQP_FW_CIA402_OPERATION_ENABLED
              ? static_cast<std::uint16_t>(MRQP_FW_CW_DISABLE_VOLTAGE)
              : mrqp_fw_cia402_master_controlword(current, d.target, d.state.controlword);
      const bool enabled =
          current == MRQP_FW_CIA402_OPERATION_ENABLED && d.target == MRQP_FW_CIA402_OPERATION_ENABLED;
      // Not enabled, or no setpoint yet: hold the measured position (raw
      // increments), no torque.
      std::int32_t position_inc = d.state.position_inc;
      std::int16_t torque_permille = 0;
      bool limited = false;
      if (enabled && d.sp_position_valid && d.cfg.mode == MRQP_FW_MODE_CSP) {
        limited = mrqp_fw_arm_position_to_inc(&d.cfg.scale, d.sp_position, &position_inc) != MRQP_FW_CONV_OK;
      }
      if (enabled && d.sp_torque_valid) {
        limited = limited || mrqp_fw_arm_torque_to_permille(&d.cfg.scale, d.sp_torque, &torque_permille) !=
                                 MRQP_FW_CONV_OK;
      }
      mrqp_fw_frame f;
      const mrqp_fw_arm_rpdo1 raw{cw, position_inc, torque_permille};
      const mrqp_fw_pack_flags pf = mrqp_fw_arm_pack_rpdo1(d.cfg.node, &raw, &f);
      if (mrqp_fw_pack_failed(pf)) {
        continue;  // cannot happen: node validated at construction
      }
      if (limited) {
        ++d.faults.limited_setpoints;
        d.events |= fault::kSetpointLimited;
      }
      d.state.controlword = cw;
      if (send(s, &d, f)) {
        ++count;
      }
    }
    if (config_.produce_sync) {
      mrqp_fw_frame f;
      slot.sync.process(now, &f);
      if (send(s, nullptr, f)) {
        ++count;
        if (!routers_.router(s).bus().echoesOwn()) {
          slot.jitter.onSync(now);  // no echo: the time handed to transmit()
        }
      }
    }
    // Feedback is expected from now on, even if the SYNC could not be queued (a
    // full queue then shows up as missing feedback, not as silence).
    slot.cyclic_sent = true;
  }
  return count;
}

Claim ArmDriver::onSdo(Drive& d, const mrqp_fw_frame& f) noexcept {
  if (phase_ == ArmPhase::Stopping || phase_ == ArmPhase::Stopped) {
    return Claim::Accepted;  // the answer to the safe exit's controlword write (or a late one)
  }
  mrqp_fw_frame out;
  switch (d.sdo.onFrame(f, &out)) {
    case SdoWriteSequence::Step::Done:
      return Claim::Accepted;
    case SdoWriteSequence::Step::Send:
      setPending(d, out);
      return Claim::Accepted;
    case SdoWriteSequence::Step::Failed:
      d.faults.sdo_abort_code = d.sdo.abortCode();
      d.faults.sdo_index = d.sdo.current().index;
      d.faults.sdo_subindex = d.sdo.current().subindex;
      failBoot(d, fault::kBootFailed);
      return Claim::Accepted;
    case SdoWriteSequence::Step::FailedSend:
      setPending(d, out);
      d.faults.sdo_abort_code = d.sdo.abortCode();
      d.faults.sdo_index = d.sdo.current().index;
      d.faults.sdo_subindex = d.sdo.current().subindex;
      ++d.faults.corrupt_frames;
      failBoot(d, fault::kBootFailed | fault::kCorruptFrame);
      return Claim::Rejected;
    case SdoWriteSequence::Step::Mismatch:
      d.faults.sdo_check_failed = true;
      d.faults.sdo_check_expected = d.sdo.current().value;
      d.faults.sdo_check_actual = d.sdo.readValue();
      d.faults.sdo_check_mask = d.sdo.current().mask;
      d.faults.sdo_index = d.sdo.current().index;
      d.faults.sdo_subindex = d.sdo.current().subindex;
      failBoot(d, fault::kBootFailed);
      return Claim::Accepted;
    case SdoWriteSequence::Step::Idle:
    case SdoWriteSequence::Step::Unexpected:
      break;
  }
  ++d.faults.corrupt_frames;
  d.events |= fault::kCorruptFrame;
  return Claim::Rejected;
}

void ArmDriver::decodeTpdo1(Drive& d, const mrqp_fw_frame& f, TimeNs t) noexcept {
  mrqp_fw_arm_tpdo1 p;
  if (mrqp_fw_arm_unpack_tpdo1(&f, d.cfg.node, &p) != MRQP_FW_OK) {
    ++d.faults.corrupt_frames;
    d.events |= fault::kCorruptFrame;
    d.last_claim = Claim::Rejected;
    return;
  }
  ArmDriveState& s = d.state;
  s.statusword = p.statusword;
  s.state = mrqp_fw_cia402_decode_statusword(p.statusword);
  s.position_inc = p.position_actual;
  s.torque_permille = p.torque_actual;
  (void)mrqp_fw_arm_position_from_inc(&d.cfg.scale, p.position_actual, &s.position);
  (void)mrqp_fw_arm_torque_from_permille(&d.cfg.scale, p.torque_actual, &s.torque);
  s.valid = true;
  s.timestamp = t;
  d.got_tpdo1 = true;
  if (s.position < d.cfg.position_min || s.position > d.cfg.position_max) {
    ++d.faults.out_of_range;
    d.events |= fault::kOutOfRange;
  }
  if (s.torque < -d.cfg.torque_limit || s.torque > d.cfg.torque_limit) {
    ++d.faults.out_of_range;
    d.events |= fault::kOutOfRange;
  }
  d.last_claim = Claim::Accepted;
}

void ArmDriver::decodeTpdo2(Drive& d, const mrqp_fw_frame& f) noexcept {
  mrqp_fw_arm_tpdo2 p;
  if (mrqp_fw_arm_unpack_tpdo2(&f, d.cfg.node, &p) != MRQP_FW_OK) {
    ++d.faults.corrupt_frames;
    d.events |= fault::kCorruptFrame;
    d.last_claim = Claim::Rejected;
    return;
  }
  ArmDriveState& s = d.state;
  s.velocity_inc = p.velocity_actual;
  (void)mrqp_fw_arm_velocity_from_inc(&d.cfg.scale, p.velocity_actual, &s.velocity);
  s.error_code = p.error_code;
  s.mode_display = p.mode_display;
  d.tpdo2_seen = true;
  if (s.velocity < -d.cfg.velocity_limit || s.velocity > d.cfg.velocity_limit) {
    ++d.faults.out_of_range;
    d.events |= fault::kOutOfRange;
  }
  d.last_claim = Claim::Accepted;
}

void ArmDriver::onOwnFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  if (slot < 0 || (rx.frame.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return;
  }
  if (rx.frame.id == MRQP_FW_COB_SYNC) {
    buses_[static_cast<std::size_t>(slot)].jitter.onSync(detail::rxTime(rx, now));
    return;
  }
  if (phase_ != ArmPhase::Resetting || rx.frame.id != MRQP_FW_COB_NMT) {
    return;
  }
  for (Drive& d : drives_) {
    if (d.cfg.bus == static_cast<std::size_t>(slot)) {
      (void)d.nmt.onOwnCommand(rx.frame);
    }
  }
}

Claim ArmDriver::onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  const mrqp_fw_frame& f = rx.frame;
  if (slot < 0 || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return Claim::NotMine;
  }
  std::uint8_t node = 0;
  const mrqp_fw_cob kind = mrqp_fw_cob_decode(f.id, &node);
  if (node == 0u || node > 127u) {
    return Claim::NotMine;
  }
  const std::int16_t index = buses_[static_cast<std::size_t>(slot)].node_to_drive[node];
  if (index < 0) {
    return Claim::NotMine;
  }
  Drive& d = drives_[static_cast<std::size_t>(index)];
  const TimeNs t = detail::rxTime(rx, now);
  switch (kind) {
    case MRQP_FW_COB_KIND_HEARTBEAT: {
      std::uint8_t n = 0;
      mrqp_fw_nmt_state st;
      if (mrqp_fw_heartbeat_unpack(&f, &n, &st) != MRQP_FW_OK) {
        break;
      }
      d.state.nmt_state = static_cast<std::uint8_t>(st);
      d.heartbeat.onHeartbeat(st, t);
      if (st == MRQP_FW_NMT_STATE_BOOTUP) {
        if (phase_ == ArmPhase::Resetting) {
          (void)d.nmt.onBootUp(t);
        } else if (phase_ == ArmPhase::Running) {
          d.events |= fault::kStateMismatch;  // the drive rebooted on its own: its
                                              // configuration is lost
          d.rebooted = true;
          d.recovery = Drive::Recovery::None;  // a recovery under way starts again
                                               // from the top
          d.faults.emcy_code = 0;              // a reboot clears the drive's errors
          d.faults.emcy_register = 0;
        } else if (phase_ != ArmPhase::Idle && phase_ != ArmPhase::Failed) {
          d.events |= fault::kStateMismatch;  // the drive rebooted on its own
        }
      }
      return Claim::Accepted;
    }
    case MRQP_FW_COB_KIND_EMCY: {
      std::uint8_t n = 0;
      mrqp_fw_emcy e;
      if (mrqp_fw_emcy_unpack(&f, &n, &e) != MRQP_FW_OK) {
        break;
      }
      ++d.faults.emcy_count;
      d.faults.emcy_code = e.error_code;
      d.faults.emcy_register = e.error_register;
      if (e.error_code != 0u) {
        d.events |= fault::kEmcy;
      }
      return Claim::Accepted;
    }
    case MRQP_FW_COB_KIND_TPDO1:
      decodeTpdo1(d, f, t);
      return d.last_claim;
    case MRQP_FW_COB_KIND_TPDO2:
      decodeTpdo2(d, f);
      return d.last_claim;
    case MRQP_FW_COB_KIND_SDO_TX:
      return onSdo(d, f);
    default:
      return Claim::NotMine;
  }
  ++d.faults.corrupt_frames;
  d.events |= fault::kCorruptFrame;
  return Claim::Rejected;
}

}  // namespace mrqp::drivers
