// The controller's cycle (see controller.hpp).
#include "loop/controller.hpp"

#include <mrqp/drivers/arm_driver.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "loop/solution_integrator.hpp"

namespace mrqp::loop {

namespace fault = drivers::fault;

const char* stopReasonStr(StopReason reason) noexcept {
  switch (reason) {
    case StopReason::None:
      return "none";
    case StopReason::QpNotOptimal:
      return "qp not optimal";
    case StopReason::DriverFault:
      return "driver fault";
    case StopReason::StaleSensor:
      return "stale sensor";
    case StopReason::NonFinite:
      return "non-finite value";
  }
  return "unknown";
}

namespace {

constexpr std::uint32_t kDefaultFatal =
    fault::kHeartbeatLost | fault::kFeedbackMissing | fault::kEmcy | fault::kDeviceFault |
    fault::kOutOfRange | fault::kSetpointRefused | fault::kCorruptFrame | fault::kBusOff |
    fault::kStateMismatch | fault::kTimeout | fault::kBootFailed | fault::kTornPair | fault::kRxOverflow;

}  // namespace

Controller::Controller(problem::MultiRobotProblem& problem, const ResolvedHardware& hw,
                       const std::vector<drivers::Bus*>& buses, const ControllerOptions& options)
    : problem_(problem),
      options_(options),
      dt_(problem.settings().dt),
      fatal_(options.fatal_flags != 0u ? options.fatal_flags : kDefaultFatal),
      feedback_missing_cycles_(hw.feedback_missing_cycles),
      loss_window_(hw.frame_loss_window),
      loss_limit_(hw.frame_loss_limit) {
  flag_first_.fill(-1);
  if (buses.size() != hw.buses.size()) {
    throw std::invalid_argument("controller: " + std::to_string(buses.size()) + " buses given for " +
                                std::to_string(hw.buses.size()) + " in the hardware section");
  }
  for (drivers::Bus* b : buses) {
    routers_.push_back(std::make_unique<drivers::BusRouter>(*b));
  }
  bus_frames_prev_.assign(buses.size(), 0);
  robots_.reserve(hw.robots.size());
  std::vector<drivers::BusRouter*> routers;
  for (auto& r : routers_) routers.push_back(r.get());
  for (std::size_t r = 0; r < hw.robots.size(); ++r) {
    robots_.push_back(makeRobotIo(hw, r, problem_.entity(hw.robots[r].entity), routers, dt_));
    commanded_.push_back(hw.robots[r].state == JointState::Commanded ? 1 : 0);
    interpolating_.push_back(hw.robots[r].interpolating_drives ? 1 : 0);
  }
  if (options_.contact_estimation) {
    std::vector<bool> measured(static_cast<std::size_t>(problem_.entityCount()), false);
    std::vector<int> imu_frame(static_cast<std::size_t>(problem_.entityCount()), -1);
    for (const RobotIo& r : robots_) {
      measured[static_cast<std::size_t>(r.entity)] = true;
      if (!r.imus.empty()) imu_frame[static_cast<std::size_t>(r.entity)] = r.imus.front().frame;
    }
    estimator_ = std::make_unique<ContactEstimator>(problem_, measured, imu_frame);
  }
  initSafety(hw);
}

bool Controller::addHook(CycleHook& hook) noexcept {
  if (hook_count_ >= kMaxHooks) return false;
  hooks_[static_cast<std::size_t>(hook_count_++)] = &hook;
  return true;
}

void Controller::startDevices(drivers::TimeNs now) noexcept {
  for (RobotIo& r : robots_) {
    for (auto& d : r.devices) d->start(now);
  }
}

bool Controller::bootCycle(drivers::TimeNs now) noexcept {
  bool all_ready = true;
  bool all_booted = true;
  const std::uint64_t k = boot_cycle_++;
  auto due = [k](const RobotIo& r) { return k % static_cast<std::uint64_t>(r.divisor) == 0u; };
  for (RobotIo& r : robots_) {
    if (!due(r)) continue;
    for (drivers::BusRouter* router : r.routers) router->poll(now);
  }
  for (RobotIo& r : robots_) {
    for (auto& d : r.devices) {
      if (!due(r)) {
        all_ready = all_ready && d->ready();
        continue;
      }
      boot_flags_ |= d->update(now).flags;
      all_ready = all_ready && d->ready();
      if (auto* arm = dynamic_cast<drivers::ArmDriver*>(d.get())) {
        all_booted = all_booted && arm->phase() == drivers::ArmPhase::Running;
      }
    }
  }
  if (all_booted && !enable_requested_) {
    enable_requested_ = true;
    for (RobotIo& r : robots_) {
      for (auto& d : r.devices) d->requestEnable(now);
    }
  }
  for (RobotIo& r : robots_) {
    if (!due(r)) continue;
    for (auto& d : r.devices) {
      // Until enabled, hold every drive where it is.
      for (const JointIo& j : r.joints) {
        if (j.device != d.get()) continue;
        const drivers::JointFeedback fb = j.device->joint(j.index);
        drivers::JointCommand c;
        c.position = fb.valid ? fb.position : 0.0;
        if (fb.valid) (void)j.device->setJoint(j.index, c);
        const std::size_t i = static_cast<std::size_t>(&j - r.joints.data());
        r.q_sent[i] = c.position;
        r.v_sent[i] = 0.0;
      }
      d->transmit(now);
    }
  }
  return all_ready;
}

void Controller::trip(StopReason reason, std::uint32_t flags, const std::string* device,
                      drivers::TimeNs now) noexcept {
  if (stop_ != StopReason::None) return;
  stop_ = reason;
  stop_flags_ = flags;
  stop_device_ = device;
  stop_cycle_ = cycle_;
  stop_time_ = now - start_;
  enterSafeState(now);
}

void Controller::read(drivers::TimeNs now) noexcept {
  for (RobotIo& r : robots_) {
    if (!robotCycle(r)) continue;
    for (drivers::BusRouter* router : r.routers) router->poll(now);
    for (auto& d : r.devices) {
      const drivers::FaultReport& rep = d->update(now);
      // A bus-off that recovered before this update shows only as an error event: it is one.
      std::uint32_t flags = rep.flags;
      for (std::size_t b = 0; b < rep.bus_count; ++b) {
        if ((rep.buses[b].error_flags & drivers::bus_error::kBusOff) != 0u) flags |= fault::kBusOff;
      }
      if (flags == 0u) continue;
      flags_seen_ |= flags;
      for (int b = 0; b < 32; ++b) {
        if (((flags >> b) & 1u) && flag_first_[static_cast<std::size_t>(b)] < 0) {
          flag_first_[static_cast<std::size_t>(b)] = now - start_;
        }
      }
      onDeviceFaults(r, *d, rep, flags, now);
    }
  }
}

void Controller::estimate(drivers::TimeNs now) noexcept {
  for (RobotIo& r : robots_) {
    if (!robotCycle(r)) continue;
    problem::Entity& e = problem_.entity(r.entity);
    const bool commanded = commanded_[static_cast<std::size_t>(&r - robots_.data())] != 0u;
    const bool interpolating = interpolating_[static_cast<std::size_t>(&r - robots_.data())] != 0u;
    for (std::size_t i = 0; i < r.joints.size(); ++i) {
      const JointIo& j = r.joints[i];
      const drivers::JointFeedback fb = j.device->joint(j.index);
      const bool missing = !fb.valid || !fb.fresh;
      // Frame loss: the rate of robot cycles without fresh feedback, averaged over
      // loss_window_ cycles, may not exceed loss_limit_.
      r.miss_rate[i] += ((missing ? 1.0 : 0.0) - r.miss_rate[i]) / loss_window_;
      if (r.miss_rate[i] > loss_limit_) {
        staleJoint(r, i, fault::kSampleLost, now);
      }
      if (missing) {
        if (++r.stale[i] > static_cast<std::uint32_t>(feedback_missing_cycles_)) {
          staleJoint(r, i, fault::kFeedbackMissing, now);
        }
        continue;
      }
      r.stale[i] = 0;
      if (!std::isfinite(fb.position) || !std::isfinite(fb.velocity)) {
        trip(StopReason::NonFinite, fault::kOutOfRange, &j.name, now);
        continue;
      }
      r.q_meas[i] = fb.position;
      r.v_meas[i] = fb.velocity;
      // The feedback was sampled at the SYNC that carried the previous setpoint: correct the
      // state predicted since then by what the joint did differently from that setpoint
      // (state: measured). A robot whose state is its command keeps the prediction: its encoders
      // are checked (above) and logged, and its tracking error is recorded. Drives that ramp to
      // each setpoint over the period sample their velocity as that ramp starts, on the ramp to
      // the setpoint before (interpolating_drives): compared with the last setpoint's velocity,
      // every change of the commanded velocity would come back, negated, as a measured one.
      const double dq = fb.position - r.q_sent[i];
      const double dv = fb.velocity - (interpolating ? r.v_sent_before[i] : r.v_sent[i]);
      if (cycle_ > 0) {
        r.tracking_error_max = std::max(r.tracking_error_max, std::fabs(dq));
      }
      if (commanded) continue;
      e.q()(j.q_index) += dq;
      e.v()(j.v_index) += dv;
    }
  }
  for (RobotIo& r : robots_) {
    if (!robotCycle(r)) continue;
    for (std::size_t i = 0; i < r.ft_sensors.size(); ++i) {
      SensorIo& s = r.ft_sensors[i];
      const drivers::WrenchFeedback w = static_cast<drivers::WrenchDevice*>(s.device)->wrench(s.index);
      if (!w.valid || !w.fresh) {
        if (++s.stale > static_cast<std::uint32_t>(feedback_missing_cycles_)) {
          trip(StopReason::StaleSensor, fault::kFeedbackMissing, &s.name, now);
        }
        continue;
      }
      s.stale = 0;
      bool finite = true;
      for (double x : w.wrench) finite = finite && std::isfinite(x);
      if (!finite) {
        trip(StopReason::NonFinite, fault::kOutOfRange, &s.name, now);
        continue;
      }
      r.wrench[i] = w.wrench;
    }
    for (std::size_t i = 0; i < r.imus.size(); ++i) {
      SensorIo& s = r.imus[i];
      const drivers::ImuFeedback m = static_cast<drivers::ImuDevice*>(s.device)->imu(s.index);
      if (!m.valid || !m.fresh) {
        if (++s.stale > static_cast<std::uint32_t>(feedback_missing_cycles_)) {
          trip(StopReason::StaleSensor, fault::kFeedbackMissing, &s.name, now);
        }
        continue;
      }
      s.stale = 0;
      r.imu[i] = m;
      if (estimator_ && i == 0) estimator_->setImu(r.entity, m);
    }
  }
  if (estimator_) estimator_->estimate();
}

void Controller::write(drivers::TimeNs now) noexcept {
  integrateSolution(problem_, dt_);
  for (RobotIo& r : robots_) {
    const problem::Entity& e = problem_.entity(r.entity);
    const auto tau = problem_.torque(r.entity);
    for (std::size_t i = 0; i < r.joints.size(); ++i) {
      const JointIo& j = r.joints[i];
      r.q_cmd[i] = e.q()(j.q_index);
      r.v_cmd[i] = e.v()(j.v_index);
      r.tau_cmd[i] = tau(j.v_index);
    }
    if (!robotCycle(r)) continue;
    for (std::size_t i = 0; i < r.joints.size(); ++i) {
      const JointIo& j = r.joints[i];
      drivers::JointCommand c;
      c.position = r.q_cmd[i];
      c.velocity = r.v_cmd[i];
      // CSP: the position alone; CST: the torque; impedance: the QP's τ as feed-forward.
      c.torque = j.kind == JointKind::Position ? 0.0 : r.tau_cmd[i];
      (void)j.device->setJoint(j.index, c);
      remember(r, i);
    }
    for (auto& d : r.devices) d->transmit(now);
  }
}

namespace {

/// A CSP target as the arm driver puts it on the wire: whole encoder increments of the drive's
/// scale (robot_io.cpp gives every CiA 402 drive the default one, 2π/524288 rad).
double cspTarget(double rad) noexcept {
  const mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  std::int32_t inc = 0;
  double out = rad;
  if (mrqp_fw_arm_position_to_inc(&scale, rad, &inc) != MRQP_FW_CONV_OK) return rad;
  (void)mrqp_fw_arm_position_from_inc(&scale, inc, &out);
  return out;
}

}  // namespace

void Controller::remember(RobotIo& r, std::size_t i) noexcept {
  // What the drive will report for this setpoint: its position, and (CSP) the velocity it derives
  // from two successive targets, both as the drive receives them (rounded to its increments: the
  // unrounded ones would feed the rounding, up to 3 mrad/s per joint, into the state's velocity
  // every robot cycle); an impedance joint the velocity commanded; a torque drive's joint is not
  // servoed: report what was predicted.
  r.v_sent_before[i] = r.v_sent[i];
  if (r.joints[i].kind != JointKind::Position) {
    r.q_sent[i] = r.q_cmd[i];
    r.v_sent[i] = r.v_cmd[i];
  } else {
    const double target = cspTarget(r.q_cmd[i]);
    r.v_sent[i] = (target - r.q_sent[i]) / (dt_ * r.divisor);
    r.q_sent[i] = target;
  }
}

void Controller::writeSafe(drivers::TimeNs now) noexcept {
  for (RobotIo& r : robots_) {
    problem::Entity& e = problem_.entity(r.entity);
    // While the recovery policy brings a drive back every robot stands still where it is (a drive
    // that dropped out no longer follows: moving the others would strain a closed chain).
    const double decay = recovering_ ? 0.0 : std::max(0.0, 1.0 - r.hold_damping * dt_);
    for (std::size_t i = 0; i < r.joints.size(); ++i) {
      const JointIo& j = r.joints[i];
      if (j.torque) {
        r.tau_cmd[i] = -options_.brake_damping * r.v_meas[i];
      } else {
        // Hold with damping: the commanded velocity decays to zero, the position follows it.
        r.v_cmd[i] *= decay;
        r.q_cmd[i] += r.v_cmd[i] * dt_;
      }
      e.q()(j.q_index) = r.q_cmd[i];
      e.v()(j.v_index) = r.v_cmd[i];
    }
    if (!robotCycle(r)) continue;
    if (stop_ != StopReason::None && r.safe_stop == SafeStop::QuickStop) {
      // The quick stop was requested in the cycle that tripped (enterSafeState).
    } else {
      for (std::size_t i = 0; i < r.joints.size(); ++i) {
        const JointIo& j = r.joints[i];
        drivers::JointCommand c;
        c.position = r.q_cmd[i];
        c.velocity = r.v_cmd[i];
        c.torque = j.torque ? r.tau_cmd[i] : 0.0;
        (void)j.device->setJoint(j.index, c);
        remember(r, i);
      }
    }
    for (auto& d : r.devices) d->transmit(now);
  }
}

void Controller::cycle(drivers::TimeNs now) noexcept {
  if (!started_) {
    started_ = true;
    start_ = now;
  }
  const drivers::TimeNs t0 = drivers::monotonicNow();
  read(now);
  const drivers::TimeNs t1 = drivers::monotonicNow();
  stepLoopRecovery(now);
  if (stop_ == StopReason::None) estimate(now);  // also while recovering: the held state follows the drives
  for (int h = 0; h < hook_count_; ++h) hooks_[static_cast<std::size_t>(h)]->onCycle(*this, now);
  const drivers::TimeNs t2 = drivers::monotonicNow();
  drivers::TimeNs t3 = t2, t4 = t2;
  if (stop_ == StopReason::None && !recovering_) {
    if (problem_.update() != problem::UpdateStatus::Ok) {
      trip(StopReason::NonFinite, 0, nullptr, now);
    }
    t3 = drivers::monotonicNow();
    if (stop_ == StopReason::None) {
      status_ = problem_.solve();
      if (status_ != qp::QpStatus::Optimal) {
        trip(StopReason::QpNotOptimal, 0, nullptr, now);
      } else if (!problem_.solution().allFinite()) {
        trip(StopReason::NonFinite, 0, nullptr, now);
      }
    }
    t4 = drivers::monotonicNow();
  }
  if (stop_ == StopReason::None && !recovering_) {
    write(now);
  } else {
    writeSafe(now);
  }
  const drivers::TimeNs t5 = drivers::monotonicNow();
  timing_.phase_ns = {t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4};
  timing_.total_ns = t5 - t0;
  logRow(now);
  ++cycle_;
}

void Controller::attachLog(LogRing& log, const std::vector<std::string>& task_names,
                           const std::vector<std::string>& contact_names) {
  auto nameOf = [](const std::vector<std::string>& names, int id, const char* what) {
    const auto i = static_cast<std::size_t>(id);
    return i < names.size() && !names[i].empty() ? names[i] : what + std::to_string(id);
  };
  log_ = &log;
  col_t_ = log.addColumn("t");
  col_phase_ = log.addColumn("read_us");
  log.addColumn("estimate_us");
  log.addColumn("update_us");
  log.addColumn("solve_us");
  log.addColumn("write_us");
  col_total_ = log.addColumn("cycle_us");
  col_status_ = log.addColumn("qp_status");
  col_iter_ = log.addColumn("qp_iterations");
  col_safe_ = log.addColumn("safe_stop");
  col_flags_ = log.addColumn("fault_flags");
  task_ids_.clear();
  for (int id = 0; id < problem_.taskCapacity(); ++id) {
    if (!problem_.taskActive(id)) continue;
    const int c = log.addColumn("err_" + nameOf(task_names, id, "task"));
    if (task_ids_.empty()) col_tasks_ = c;
    task_ids_.push_back(id);
  }
  for (int id = 0; id < problem_.contactCapacity(); ++id) {
    if (!problem_.contactActive(id)) continue;
    const std::string name = nameOf(contact_names, id, "contact");
    const int c = log.addColumn("fx_" + name);
    log.addColumn("fy_" + name);
    log.addColumn("fz_" + name);
    if (contact_ids_.empty()) col_contacts_ = c;
    contact_ids_.push_back(id);
  }
  for (const RobotIo& r : robots_) {
    for (const JointIo& j : r.joints) {
      const int c = log.addColumn("cmd_" + j.name);
      log.addColumn("fb_" + j.name);
      if (col_joints_ < 0) col_joints_ = c;
    }
  }
  for (const RobotIo& r : robots_) {
    for (const SensorIo& f : r.ft_sensors) {
      const int c = log.addColumn("ft_" + f.name + "_fx");
      log.addColumn("ft_" + f.name + "_fy");
      log.addColumn("ft_" + f.name + "_fz");
      if (col_ft_ < 0) col_ft_ = c;
    }
  }
  for (std::size_t b = 0; b < routers_.size(); ++b) {
    const int c = log.addColumn("frames_bus" + std::to_string(b));
    if (b == 0) col_buses_ = c;
  }
}

void Controller::logRow(drivers::TimeNs now) noexcept {
  if (log_ == nullptr) return;
  double* row = log_->beginRow();
  if (row == nullptr) return;
  row[col_t_] = static_cast<double>(now - start_) * 1e-9;
  for (int p = 0; p < kPhaseCount; ++p)
    row[col_phase_ + p] = static_cast<double>(timing_.phase_ns[static_cast<std::size_t>(p)]) * 1e-3;
  row[col_total_] = static_cast<double>(timing_.total_ns) * 1e-3;
  row[col_status_] = static_cast<double>(static_cast<int>(status_));
  row[col_iter_] = static_cast<double>(problem_.solver().info().iterations);
  row[col_safe_] = static_cast<double>(static_cast<int>(stop_));
  row[col_flags_] = static_cast<double>(flags_seen_);
  for (std::size_t i = 0; i < task_ids_.size(); ++i) {
    row[col_tasks_ + static_cast<int>(i)] = problem_.taskError(task_ids_[i]).norm();
  }
  for (std::size_t i = 0; i < contact_ids_.size(); ++i) {
    const Eigen::Vector3d f = problem_.contactForce(contact_ids_[i]);
    for (int k = 0; k < 3; ++k) row[col_contacts_ + 3 * static_cast<int>(i) + k] = f(k);
  }
  int c = col_joints_;
  for (const RobotIo& r : robots_) {
    for (std::size_t i = 0; i < r.joints.size(); ++i) {
      row[c++] = r.q_cmd[i];
      row[c++] = r.q_meas[i];
    }
  }
  c = col_ft_;
  for (const RobotIo& r : robots_) {
    for (std::size_t i = 0; i < r.ft_sensors.size(); ++i) {
      for (std::size_t k = 0; k < 3; ++k) row[c++] = r.wrench[i][k];
    }
  }
  for (std::size_t b = 0; b < routers_.size(); ++b) {
    const drivers::BusStatus s = routers_[b]->bus().status();
    const std::uint64_t frames = s.tx_frames + s.rx_frames;
    row[col_buses_ + static_cast<int>(b)] = static_cast<double>(frames - bus_frames_prev_[b]);
    bus_frames_prev_[b] = frames;
  }
  for (const LogValues& x : log_values_) {
    for (int i = 0; i < x.count; ++i) row[x.first + i] = x.values[i];
  }
  log_->commit();
}

void Controller::attachLogValues(LogRing& log, const std::vector<std::string>& names, const double* values) {
  if (names.empty()) return;
  LogValues x;
  x.first = log.addColumn(names.front());
  for (std::size_t i = 1; i < names.size(); ++i) log.addColumn(names[i]);
  x.count = static_cast<int>(names.size());
  x.values = values;
  log_values_.push_back(x);
}

}  // namespace mrqp::loop
