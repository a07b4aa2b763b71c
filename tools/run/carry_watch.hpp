// What a carrying scene did to the object it carries (docs/force-control.md, "carry_box"),
// measured on the plant's state between cycles — never on the controller's estimate:
//
//   box_waypoint_errors_m  per waypoint of the object's trajectory (waypoint_trajectory.hpp): the
//                          distance of the plant's object to the waypoint at the first cycle at or
//                          after the time it should be reached (null when the run ended before);
//   box_slip_m             the largest displacement of the object's origin in the frame of a hand
//                          that holds it (a contact of the scene between the object and a robot
//                          frame) from where it was in that frame at the first cycle;
//   box_dropped            true when, after the trajectory's start, the plant's object was ever more
//                          than `drop_margin` (0.05 m) below the trajectory's reference height.
//
// It also keeps a time series (the object's reference and plant position, each hand frame's
// position, each admittance's target and measured force) written to DIR/carry.csv and drawn by
// gnuplot to DIR/carry_box.png (the object against its waypoints and the hands, as the paper's
// Fig. 14, and the hands' forces). The frames come from a second problem of the scene whose
// entities are moved to the plant's states. Host-side (between cycles): sample() does not allocate
// once the series has its capacity; the rest allocates.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

#include "force/admittance_hook.hpp"
#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"
#include "scene/scene_builder.hpp"
#include "waypoint_trajectory.hpp"

namespace mrqp::run {

class CarryWatch {
 public:
  static constexpr double kDropMargin = 0.05;  ///< m

  /// `model`: the controller's scene; `shadow`: a second problem of the same scene (same entities);
  /// the object is the entity of the trajectory's first item's task. `admittance`: the forces
  /// of its end-effectors are kept for the plot (nullptr: none). `duration`: the run's length, s (sizes the series: one sample every `every` s).
  CarryWatch(const scene::Scene& model, problem::MultiRobotProblem& shadow, const loop::Plant& plant,
             const WaypointTrajectory& trajectory, const force::AdmittanceHook* admittance, double duration,
             double every = 0.01);

  /// True when the scene carries a rigid object along a trajectory (else nothing is measured).
  bool enabled() const noexcept { return object_ >= 0; }

  /// After the cycle that ran at time t (s since the first cycle): the plant's state.
  void sample(double t);

  const std::vector<double>& waypointErrors() const noexcept { return waypoint_error_; }
  double slip() const noexcept { return slip_; }
  bool dropped() const noexcept { return dropped_; }
  /// summary.json's members (JSON text) for these results and `force_control`.
  std::vector<std::pair<std::string, std::string>> summaryFields(bool force_control) const;

  /// DIR/carry.csv and DIR/carry_box.png; returns the files written, `error` says what failed.
  std::vector<std::string> write(const std::string& dir, const std::string& title, std::string* error) const;

 private:
  struct Hand {
    std::string name;  // the contact's name
    int entity = -1, frame = -1;
    Eigen::Vector3d rel0 = Eigen::Vector3d::Zero();  // the object's origin in the hand frame, first sample
  };
  void plantState(int entity);

  problem::MultiRobotProblem& shadow_;
  const loop::Plant& plant_;
  const WaypointTrajectory& trajectory_;
  const force::AdmittanceHook* admittance_;
  int end_effectors_ = 0;
  int object_ = -1, object_frame_ = -1, plant_object_ = -1;
  std::vector<int> plant_handle_;  // per entity of the scene (−1: none)
  std::vector<Hand> hands_;
  std::vector<double> waypoint_error_;
  double every_ = 0.01, next_ = 0.0;
  bool first_ = true;
  double slip_ = 0.0;
  bool dropped_ = false;
  int columns_ = 0;
  std::vector<double> series_;  // rows of columns_
};

}  // namespace mrqp::run
