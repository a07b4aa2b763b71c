// Fault injection (see fault_injector.hpp).
#include "loop/fault_injector.hpp"

#include <cstdlib>
#include <stdexcept>

namespace mrqp::loop {

namespace {
double faultTime(const std::string& spec, const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0')
    throw std::invalid_argument("--fault " + spec + ": expected a time in s, got '" + v + "'");
  return d;
}
}  // namespace

FaultRequest parseFaultRequest(const std::string& spec) {
  static const char* kinds[] = {"heartbeat-loss", "bus-off",  "frame-loss", "corrupt-frames",
                                "nan-feedback",   "stale-ft", "infeasible"};
  const std::size_t at = spec.find('@');
  if (at == std::string::npos)
    throw std::invalid_argument("--fault " + spec + ": expected KIND@SECONDS[:DEVICE]");
  FaultRequest f;
  f.kind = spec.substr(0, at);
  bool known = false;
  for (const char* k : kinds) known = known || f.kind == k;
  if (!known) {
    throw std::invalid_argument(
        "--fault " + spec + ": unknown kind '" + f.kind +
        "' (heartbeat-loss, bus-off, frame-loss, corrupt-frames, nan-feedback, stale-ft, "
        "infeasible)");
  }
  const std::string rest = spec.substr(at + 1);
  const std::size_t colon = rest.find(':');
  f.at_s = faultTime(spec, rest.substr(0, colon));
  if (!(f.at_s >= 0.0)) throw std::invalid_argument("--fault " + spec + ": the time must be >= 0");
  if (colon != std::string::npos) {
    f.device = rest.substr(colon + 1);
    if (f.device.empty()) throw std::invalid_argument("--fault " + spec + ": empty device after ':'");
  }
  return f;
}

FaultInjector::FaultInjector(const std::vector<FaultRequest>& requests, EmulatedRig* rig,
                             Controller& controller, const ResolvedHardware& hw)
    : rig_(rig), controller_(controller) {
  for (const FaultRequest& q : requests) {
    FaultRecord r;
    r.kind = q.kind;
    r.at_s = q.at_s;
    Target t;
    const std::string spec =
        "--fault " + q.kind + "@" + std::to_string(q.at_s) + (q.device.empty() ? "" : ":" + q.device);
    if (q.kind == "stale-ft") {
      if (rig == nullptr) {
        throw std::invalid_argument(spec + ": hardware faults are injected in the emulated rig (--bus sim)");
      }
      t.ft = rig->ftSensor(q.device);
      if (t.ft == nullptr) {
        throw std::invalid_argument(spec + ": no F/T sensor " +
                                    (q.device.empty()
                                         ? "in the hardware section"
                                         : "'" + q.device + "' (an F/T sensor is ENTITY.FRAME)"));
      }
      r.device = rig->ftSensorName(t.ft);
    } else if (q.kind == "infeasible") {
      // A joint of a robot: DEVICE "ENTITY.JOINT", else the first driven joint.
      for (std::size_t ri = 0; ri < controller.robots().size() && t.robot < 0; ++ri) {
        const RobotIo& rob = controller.robots()[ri];
        for (const JointIo& j : rob.joints) {
          if (q.device.empty() || q.device == j.name) {
            t.robot = static_cast<int>(ri);
            t.joint = j.v_index;
            r.device = j.name;
            break;
          }
        }
      }
      if (t.robot < 0)
        throw std::invalid_argument(spec + ": no driven joint " +
                                    (q.device.empty() ? "" : "'" + q.device + "'"));
    } else {
      if (rig == nullptr) {
        throw std::invalid_argument(spec + ": hardware faults are injected in the emulated rig (--bus sim)");
      }
      if (q.kind == "bus-off") {
        for (std::size_t b = 0; b < hw.buses.size(); ++b) {
          if (q.device.empty() || q.device == hw.buses[b].decl.name) {
            t.bus = static_cast<int>(b);
            r.device = hw.buses[b].decl.name;
            break;
          }
        }
        if (t.bus < 0)
          throw std::invalid_argument(spec + ": no bus '" + q.device + "' in the hardware section");
      } else if (!q.device.empty() &&
                 (rig->mitMotor(q.device) != nullptr || rig->handBoard(q.device) != nullptr)) {
        if (q.kind != "heartbeat-loss" && q.kind != "corrupt-frames" && q.kind != "nan-feedback") {
          throw std::invalid_argument(spec +
                                      ": not emulated for MIT motors and hand boards "
                                      "(heartbeat-loss, corrupt-frames and nan-feedback are)");
        }
        t.mit = rig->mitMotor(q.device);
        t.board = rig->handBoard(q.device);
        r.device = q.device;
      } else {
        t.drive = q.device.empty() ? rig->firstDrive() : rig->drive(q.device);
        if (t.drive == nullptr) {
          throw std::invalid_argument(spec + ": no drive " + (q.device.empty() ? "" : "'" + q.device + "' ") +
                                      "(a drive is ENTITY.JOINT)");
        }
        r.device = rig->driveName(t.drive);
      }
    }
    records_.push_back(r);
    targets_.push_back(t);
  }
}

void FaultInjector::beforeCycle(double t, drivers::TimeNs now) noexcept {
  for (std::size_t i = 0; i < records_.size(); ++i) {
    FaultRecord& r = records_[i];
    const Target& tg = targets_[i];
    if (r.injected_at_s >= 0.0 || t + 1e-12 < r.at_s) continue;
    r.injected_at_s = t;
    if (tg.mit != nullptr || tg.board != nullptr) {
      // The hand actuators' own faults: silence, corrupt replies, a tripped controller.
      if (r.kind == "heartbeat-loss") {
        if (tg.mit != nullptr) tg.mit->setSilent(true);
        if (tg.board != nullptr) tg.board->setSilent(true);
      } else if (r.kind == "corrupt-frames") {
        if (tg.mit != nullptr) tg.mit->corruptReplies(1000000u);
        if (tg.board != nullptr) tg.board->corruptFeedback(1000000u);
      } else if (r.kind == "nan-feedback") {
        if (tg.mit != nullptr) tg.mit->raiseFault(now);
        if (tg.board != nullptr) tg.board->raiseFault(now);
      }
    } else if (r.kind == "heartbeat-loss") {
      tg.drive->stopHeartbeat(now);
    } else if (r.kind == "frame-loss") {
      tg.drive->setFrameLoss(50);  // 5 %
    } else if (r.kind == "corrupt-frames") {
      tg.drive->setCorruptFrames(true);
    } else if (r.kind == "nan-feedback") {
      tg.drive->breakEncoder();
    } else if (r.kind == "bus-off") {
      rig_->master(static_cast<std::size_t>(tg.bus)).injectTxErrors(40);  // TEC 8 × 40 > 255
    } else if (r.kind == "stale-ft") {
      tg.ft->firmware().setStale(true);  // the ADC stopped: the last values repeat, status STALE
    } else if (r.kind == "infeasible") {
      problem::MultiRobotProblem& p = controller_.problem();
      const RobotIo& rob = controller_.robots()[static_cast<std::size_t>(tg.robot)];
      const problem::Entity& e = p.entity(rob.entity);
      problem::JointInequalityDesc d;
      d.terms = 1;
      d.entity[0] = rob.entity;
      d.joint[0] = tg.joint;
      d.coeff[0] = 1.0;
      d.upper = e.q()(e.qIndexOfV(tg.joint)) - 1.0;  // q ≤ q_now − 1 rad, now
      d.interaction = 0.05;
      d.security = 0.0;
      d.damping = 0.5;
      (void)p.addJointInequality(d);
    }
  }
}

void FaultInjector::afterCycle() noexcept {
  if (!controller_.safeStopped()) return;
  const double stop = static_cast<double>(controller_.stopTime()) * 1e-9;
  for (FaultRecord& r : records_) {
    if (r.injected_at_s < 0.0 || r.detected_at_s >= 0.0) continue;
    if (stop + 1e-12 < r.injected_at_s) continue;  // stopped before this fault: not its detection
    r.detected_at_s = stop;
    r.safe_state_at_s = stop;  // the safe commands go out in the cycle that detects
  }
}

}  // namespace mrqp::loop
