// The `trajectories:` section of a scene file (docs/force-control.md, "carry_box"): a frame task
// whose position reference moves through waypoints, each reached at a given time, with position,
// velocity and acceleration references (eq. 26) that are continuous: between two waypoints a and b
// (times t_a, t_b, T = t_b − t_a, τ = (t − t_a)/T) the reference follows the minimum-jerk profile
//
//   g(t) = a + (b − a) s(τ),  s(τ) = 10τ³ − 15τ⁴ + 6τ⁵,  ġ = (b − a) s'(τ)/T,  g̈ = (b − a) s''(τ)/T²,
//
// at rest on each waypoint. Before `start` the reference is the task's target of the scene, after
// the last waypoint it stays there. Tasks listed in `carry` (other frame tasks, e.g. the hands of
// the robots carrying the object) are translated with the reference: their target is their scene
// target plus g(t) − g(0), with the same velocity and acceleration references.
//
// Played by mrqp-run as a loop::CycleHook, registered before the admittance (which then takes a
// carried hand task's moving target as its nominal position). Reading resolves names against the
// built scene (errors "FILE:LINE: FIELD: message"); onCycle is noexcept and allocation-free.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "loop/controller.hpp"
#include "scene/scene_builder.hpp"

namespace mrqp::run {

struct Waypoint {
  double at = 0.0;  ///< s since the first cycle: when the reference reaches it
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

/// The reference of a trajectory at one time.
struct TrajectoryPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
};

/// One item of the section: a task and its waypoints.
struct TrajectorySpec {
  std::string task_name;
  int task = -1;
  double start = 0.0;
  Eigen::Vector3d initial = Eigen::Vector3d::Zero();  ///< the task's target in the scene
  std::vector<Waypoint> waypoints;                    ///< strictly increasing times, after start
  std::vector<int> carried;                           ///< task ids
  std::vector<Eigen::Vector3d> carried_initial;       ///< their scene targets
};

/// The minimum-jerk profile s(τ), s'(τ), s''(τ) on [0, 1] (clamped outside).
Eigen::Vector3d minimumJerk(double tau) noexcept;

class WaypointTrajectory final : public loop::CycleHook {
 public:
  /// The `trajectories:` section of the scene held in `text` (empty when it has none).
  static WaypointTrajectory read(const std::string& text, const std::string& file, const scene::Scene& scene);

  /// Reference of item `i` at time t (s since the first cycle).
  TrajectoryPoint at(std::size_t i, double t) const noexcept;
  const std::vector<TrajectorySpec>& items() const noexcept { return items_; }
  bool empty() const noexcept { return items_.empty(); }

  /// Writes every item's task (and the tasks it carries): target and references at the cycle's time.
  void onCycle(loop::Controller& controller, drivers::TimeNs now) noexcept override;
  /// The same on a problem at time t (tests, programs without a controller).
  void apply(problem::MultiRobotProblem& problem, double t) const noexcept;

 private:
  std::vector<TrajectorySpec> items_;
};

}  // namespace mrqp::run
