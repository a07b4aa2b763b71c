// mrqp-run's recorder of the force control (docs/force-control.md, "Results of a run"): per
// end-effector of the scene's force_control section, every loop cycle, the user force fᵈ, the
// admittance's target and sensed force along the normal, its velocity, and the largest |τ| / τ_max
// over the joints of the end-effector's chain in the plant; after the run summary.json's `hands`,
// DIR/force.csv and the plots force_tracking.png (target and sensed force, as the paper's Fig. 7)
// and torque_limits.png (|τ| / τ_max of the chain, as Fig. 8's torque limits).
//
// torque_limit_hits: the loop cycles in which at least one joint of the end-effector's chain has
// |τ| ≥ (1 − 10⁻³) × its URDF effort limit, τ being the plant's drive torque after the cycle's step
// (Plant::jointTorque, what the drive's current sensor reads). The chain: the joints between the
// robot's root and the F/T sensor's frame that are not also ancestors of another end-effector's
// sensor frame of the same robot (JVRC-1's arm, without the waist its two arms share). −1 when
// there is no plant to read (SocketCAN buses).
//
// The record's storage is sized at construction; sample() does not allocate.
#pragma once

#include <string>
#include <vector>

#include "force/admittance_hook.hpp"
#include "hand_summary.hpp"
#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::run {

class HandsRecorder {
 public:
  /// Seconds after the start and after each change of mode or fᵈ that the RMS leaves out (the
  /// admittance's transient), rounded to loop cycles.
  static constexpr double kSettleS = 0.5;
  /// |τ| ≥ (1 − kLimitTolerance) τ_max counts as at the limit.
  static constexpr double kLimitTolerance = 1e-3;

  /// `plant` may be null (no torques). Storage for `cycles` loop cycles.
  HandsRecorder(const force::AdmittanceHook& hook, const problem::MultiRobotProblem& p,
                const loop::Plant* plant, long cycles, double dt);

  bool empty() const noexcept { return hands_.empty(); }
  /// After cycle k: the admittances' states and the chains' torques. noexcept, no allocation.
  void sample(long k) noexcept;

  std::vector<HandSummary> summary() const;
  /// DIR/force.csv and, with `plots`, the two plots (gnuplot); the files written, `error` says
  /// what failed.
  std::vector<std::string> write(const std::string& dir, const std::string& title, bool plots,
                                 std::string* error) const;

 private:
  struct Joint {
    int plant_joint = -1;
    double limit = 0.0;
  };
  struct Hand {
    std::string name;
    std::vector<Joint> chain;
    // per loop cycle
    std::vector<double> fd, target, measured, velocity, ratio;
    std::vector<unsigned char> hit, counted, mode;
    int last_mode = -1;
    double last_fd = 0.0;
    long changed_at = 0;  // the loop cycle of the last change of mode or fᵈ
  };
  const force::AdmittanceHook& hook_;
  const loop::Plant* plant_;
  double dt_;
  long settle_cycles_;
  long samples_ = 0;
  std::vector<Hand> hands_;
};

}  // namespace mrqp::run
