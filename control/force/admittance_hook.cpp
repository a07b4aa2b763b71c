// The force control of Sec. III on the controller's cycle (see admittance_hook.hpp).
#include "force/admittance_hook.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mrqp::force {

AdmittanceHook::AdmittanceHook(loop::Controller& controller, const ForceControlSpec& spec, bool disabled)
    : controller_(controller), events_(spec.events), disabled_(disabled) {
  problem::MultiRobotProblem& p = controller.problem();
  const double dt = controller.period();
  slots_.reserve(spec.end_effectors.size());
  for (const EndEffectorSpec& e : spec.end_effectors) {
    const std::string what = "force_control: end-effector '" + e.name + "': ";
    if (e.entity < 0 || e.entity >= p.entityCount() || e.task < 0 || e.task >= p.taskCapacity()) {
      throw std::invalid_argument(what + "its entity or task is not in the problem");
    }
    slots_.emplace_back(e, 1.0 / (dt * std::max(1, e.divisor)));
    Slot& s = slots_.back();
    s.frame_task = dynamic_cast<const problem::FrameTask*>(&p.task(e.task));
    if (s.frame_task == nullptr || s.frame_task->entity() != e.entity) {
      throw std::invalid_argument(what + "its task is not a frame task of its entity");
    }
    s.rows = p.task(e.task).referenceRows();
    const std::vector<loop::RobotIo>& robots = controller.robots();
    for (std::size_t r = 0; r < robots.size(); ++r) {
      if (robots[r].entity != e.entity) continue;
      s.robot = static_cast<int>(r);
      if (robots[r].divisor != e.divisor) throw std::invalid_argument(what + "the robot's divisor differs");
      for (std::size_t k = 0; k < robots[r].ft_sensors.size(); ++k) {
        if (robots[r].ft_sensors[k].frame == e.sensor_frame) s.sensor = static_cast<int>(k);
      }
    }
    if (s.robot < 0 || s.sensor < 0)
      throw std::invalid_argument(what + "the controller has no such F/T sensor");
    if (e.contact >= 0) {
      if (e.contact >= p.contactCapacity())
        throw std::invalid_argument(what + "its contact is not in the problem");
      s.sign = p.contact(e.contact).entity == e.entity ? -1.0 : 1.0;
    }
    s.nominal = s.written = s.frame_task->target();
    s.st.position_ref = s.nominal;
    s.st.force = e.force;
    s.st.mode = disabled ? ForceMode::Off : e.mode;
    if (e.force_task >= 0) {
      if (forceTaskOn(s.st.mode)) {
        if (!p.taskActive(e.force_task)) p.restoreTask(e.force_task);
      } else {
        p.removeTask(e.force_task);
      }
    }
  }
}

bool AdmittanceHook::setMode(int i, ForceMode mode) noexcept {
  if (i < 0 || i >= size() || disabled_) return false;
  Slot& s = slot(i);
  if ((targetFromQp(mode) && s.spec.contact < 0) || (forceTaskOn(mode) && s.spec.force_task < 0))
    return false;
  if (s.spec.force_task >= 0 && forceTaskOn(mode) != forceTaskOn(s.st.mode)) {
    problem::MultiRobotProblem& p = controller_.problem();
    if (forceTaskOn(mode)) {
      p.restoreTask(s.spec.force_task);
    } else {
      p.removeTask(s.spec.force_task);
    }
  }
  s.st.mode = mode;
  return true;
}

bool AdmittanceHook::setForce(int i, double force) noexcept {
  if (i < 0 || i >= size() || !std::isfinite(force)) return false;
  slot(i).st.force = force;
  return true;
}

void AdmittanceHook::robotCycle(loop::Controller& c, Slot& s) noexcept {
  problem::MultiRobotProblem& p = c.problem();
  const problem::Entity& e = p.entity(s.spec.entity);
  State& st = s.st;
  // The normal in world axes (the entity's kinematics of the last update).
  const problem::Pose task_pose = e.framePose(s.frame_task->frame());
  if (s.spec.normal_in_world) {
    st.normal = s.spec.normal;
  } else {
    st.normal = task_pose.R * s.spec.normal;
  }
  const Eigen::Vector3d& n = st.normal;

  // The sensed force the end-effector applies, along n.
  const loop::RobotIo& robot = c.robots()[static_cast<std::size_t>(s.robot)];
  const loop::SensorIo& io = robot.ft_sensors[static_cast<std::size_t>(s.sensor)];
  const std::array<double, 6>& w = robot.wrench[static_cast<std::size_t>(s.sensor)];
  const Eigen::Vector3d sample(w[0], w[1], w[2]);
  const Eigen::Matrix3d R_sensor = e.framePose(s.spec.sensor_frame).R;
  const Eigen::Vector3d applied = s.spec.tool_mass * p.settings().gravity - R_sensor * sample;
  const double measured = applied.dot(n);

  // The QP's force through the contact (the previous solution), as the end-effector applies it.
  Eigen::Vector3d qp_applied = Eigen::Vector3d::Zero();
  if (s.spec.contact >= 0 && p.contactActive(s.spec.contact))
    qp_applied = s.sign * p.contactForce(s.spec.contact);
  const double qp_normal = qp_applied.dot(n);
  const double target = targetFromQp(st.mode) ? qp_normal : st.force;

  const bool ok = st.mode != ForceMode::Off && io.stale == 0u && !c.safeStopped() &&
                  std::isfinite(measured) && std::isfinite(target) && n.allFinite();
  s.v_old = s.v_new;
  s.v_new = s.law.step(target, measured, ok, st.normal_displacement);
  s.phase = 0;
  st.target = target;
  st.measured = measured;
  st.velocity = s.v_new;
  st.clamped = s.law.clamped();
  st.holding = s.law.holding();
  if (st.holding && st.mode != ForceMode::Off) ++st.holds;

  // Switch 1 closed: fᵈ along n into the QP's force task, the tangential part left as it was.
  if (forceTaskOn(st.mode) && s.spec.force_task >= 0 && std::isfinite(st.force)) {
    const Eigen::Vector3d wanted = qp_applied + (st.force - qp_normal) * n;
    (void)p.setTaskTarget(s.spec.force_task, s.sign * wanted);
  }
}

void AdmittanceHook::writeReferences(problem::MultiRobotProblem& p, Slot& s, double dt) noexcept {
  State& st = s.st;
  const int D = std::max(1, s.spec.divisor);
  s.phase = std::min(s.phase + 1, D);
  const double v = s.v_old + (s.v_new - s.v_old) * static_cast<double>(s.phase) / static_cast<double>(D);
  const double a = (s.v_new - s.v_old) / (static_cast<double>(D) * dt);
  st.velocity_ref = v * st.normal;
  st.acceleration_ref = a * st.normal;
  st.displacement += st.velocity_ref * dt;
  st.normal_displacement += v * dt;
  // A position target moved by something else becomes the nominal position.
  if (s.frame_task->target() != s.written) s.nominal = s.frame_task->target();
  st.position_ref = s.nominal + st.displacement;
  if (s.rows == 3) {
    (void)p.setTaskReference(s.spec.task, st.position_ref, st.velocity_ref, st.acceleration_ref);
  } else {
    problem::Vector6d vel, acc;
    vel << Eigen::Vector3d::Zero(), st.velocity_ref;
    acc << Eigen::Vector3d::Zero(), st.acceleration_ref;
    if (p.setTaskTarget(s.spec.task, st.position_ref)) (void)p.setTaskReference(s.spec.task, vel, acc);
  }
  // What the task holds now (unchanged while it is switched off).
  s.written = s.frame_task->target();
}

void AdmittanceHook::onCycle(loop::Controller& c, drivers::TimeNs) noexcept {
  const double t = static_cast<double>(c.cycles()) * c.period();
  while (next_event_ < events_.size() && events_[next_event_].at <= t + 1e-12) {
    const ForceEvent& ev = events_[next_event_++];
    if (ev.set_force) (void)setForce(ev.end_effector, ev.force);
    if (ev.set_mode) (void)setMode(ev.end_effector, ev.mode);
  }
  problem::MultiRobotProblem& p = c.problem();
  for (Slot& s : slots_) {
    if (c.cycles() % static_cast<std::uint64_t>(std::max(1, s.spec.divisor)) == 0u) robotCycle(c, s);
    writeReferences(p, s, c.period());
  }
}

}  // namespace mrqp::force
