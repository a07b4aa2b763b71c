// The force control of Sec. III on the controller's cycle (docs/force-control.md): one
// loop::CycleHook that runs the admittance of every end-effector of the scene's force_control
// section between the estimate and the QP update.
//
// On each of its robot's cycles (the loop period × the robot's divisor: the F/T sample's rate) an
// end-effector
//   - takes the wrench its F/T sensor sent (the controller's last fresh sample, sensor axes: what
//     the tool side exerts on the arm side), rotates it into the world through the sensor frame's
//     pose, removes the tool's weight and reads the force the end-effector applies on what it
//     touches along the world normal n: f_sensor = ⟨m_tool g − R f_sample | n⟩;
//   - takes its target (switch 2, force_mode.hpp): fᵈ, or the force that the QP's previous
//     solution applies through the end-effector's contact along n;
//   - steps its Admittance (eq. 45–46 and the Butterworth filter) into ṽ, with the displacement
//     along n so far (the admittance's bound, max_displacement); it holds (feeds the filter
//     zero) when the sample is stale or not finite, when the controller has stopped and in mode
//     off;
//   - with switch 1 closed, sets the target of the scene's force task: the QP's previous contact
//     force with its component along n replaced by fᵈ (the tangential components are left where
//     the QP put them).
// Every loop cycle the task of the end-effector (frame_position or frame_pose) gets its
// references: ġʳᵉᶠ = v n with v ramping linearly from the previous ṽ to the new one over the
// robot cycle, g̈ʳᵉᶠ = the ramp's slope × n, gʳᵉᶠ = the task's nominal position + the integral of
// ġʳᵉᶠ (d, the admittance's displacement). When something else moves the task's position target
// (a timeline event), that becomes the nominal position and d is kept on top of it.
//
// Mode and fᵈ change at run time (setMode, setForce, the timeline's force_control events) with
// the filter's state kept: the commanded velocity moves continuously. Set-up (the constructor)
// allocates and throws; onCycle, setMode and setForce are noexcept and allocation-free.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "force/admittance.hpp"
#include "force/force_control_spec.hpp"
#include "loop/controller.hpp"
#include "problem/tasks/frame_task.hpp"

namespace mrqp::force {

class AdmittanceHook final : public loop::CycleHook {
 public:
  /// What one end-effector did on its last cycle (logs, tests, summaries).
  struct State {
    ForceMode mode = ForceMode::Off;
    double force = 0.0;                                 ///< fᵈ, N
    double target = 0.0;                                ///< f_target along n, N (the QP's force or fᵈ)
    double measured = 0.0;                              ///< f_sensor along n, N
    double velocity = 0.0;                              ///< ṽ, m/s (the filter's output)
    double clamped = 0.0;                               ///< v_c, m/s (the filter's input)
    bool holding = false;                               ///< the admittance held on its last robot cycle
    std::uint64_t holds = 0;                            ///< robot cycles held while the mode was not off
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< n in world axes
    Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
    double normal_displacement = 0.0;  ///< s: the displacement along n, ∫ṽ dt, m (bounded)
    Eigen::Vector3d position_ref = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity_ref = Eigen::Vector3d::Zero();
    Eigen::Vector3d acceleration_ref = Eigen::Vector3d::Zero();
  };

  /// Binds every end-effector of `spec` to the controller's F/T sensor and the problem's tasks
  /// and applies the initial modes (force tasks switched on or off). `disabled`: every
  /// end-effector runs in mode off and the timeline's mode changes are ignored (a run without
  /// force control). Throws std::invalid_argument when the controller does not match the spec.
  AdmittanceHook(loop::Controller& controller, const ForceControlSpec& spec, bool disabled = false);

  void onCycle(loop::Controller& controller, drivers::TimeNs now) noexcept override;

  int size() const noexcept { return static_cast<int>(slots_.size()); }
  const EndEffectorSpec& spec(int i) const noexcept { return slot(i).spec; }
  const State& state(int i) const noexcept { return slot(i).st; }
  const Admittance& admittance(int i) const noexcept { return slot(i).law; }

  /// A new mode from the next robot cycle; false (nothing changed) when the end-effector lacks
  /// what the mode needs (a contact, a force task) or force control is disabled.
  bool setMode(int i, ForceMode mode) noexcept;
  /// A new fᵈ (N along n); false when not finite.
  bool setForce(int i, double force) noexcept;
  /// Timeline events played so far.
  std::size_t eventsPlayed() const noexcept { return next_event_; }

 private:
  struct Slot {
    Slot(const EndEffectorSpec& s, double sample_hz) : spec(s), law(s.gains, sample_hz) {}
    EndEffectorSpec spec;
    Admittance law;
    const problem::FrameTask* frame_task = nullptr;
    int robot = -1;   // index into Controller::robots()
    int sensor = -1;  // index into that robot's ft_sensors
    int rows = 3;     // the task's rows: 3 (position) or 6 (pose, angular first)
    double sign = 1;  // the force the end-effector applies = sign × contactForce(contact)
    double v_old = 0.0, v_new = 0.0;
    int phase = 0;  // loop cycles since the last robot cycle
    Eigen::Vector3d nominal = Eigen::Vector3d::Zero(), written = Eigen::Vector3d::Zero();
    State st;
  };
  Slot& slot(int i) noexcept { return slots_[static_cast<std::size_t>(i)]; }
  const Slot& slot(int i) const noexcept { return slots_[static_cast<std::size_t>(i)]; }
  void robotCycle(loop::Controller& c, Slot& s) noexcept;
  void writeReferences(problem::MultiRobotProblem& p, Slot& s, double dt) noexcept;

  loop::Controller& controller_;
  std::vector<Slot> slots_;
  std::vector<ForceEvent> events_;
  std::size_t next_event_ = 0;
  bool disabled_ = false;
};

}  // namespace mrqp::force
