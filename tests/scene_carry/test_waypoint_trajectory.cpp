// The waypoint trajectory of tools/run (waypoint_trajectory.hpp): the minimum-jerk profile against
// its closed-form boundary values and finite differences, the reference through the waypoints, the
// references written to the box task and to the tasks it carries, and the section's errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "problem/tasks/frame_task.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "waypoint_trajectory.hpp"

using namespace mrqp;

namespace {

// A box held by nothing and a second box carried with it: enough for frame tasks.
const char* kScene = R"(settings: {dt: 0.001, max_tasks: 4}
entities:
  - {name: box, model: rigid_object, mass: 2.0, inertia: [0.05, 0.02, 0.05], pose: {xyz: [0.3, 0, 1.0]}}
  - {name: lid, model: rigid_object, mass: 0.5, inertia: [0.01, 0.01, 0.01], pose: {xyz: [0.3, 0, 1.2]}}
tasks:
  - {name: box_pose, type: frame_pose, entity: box, frame: box, target: [0.3, 0, 1.0, 0, 0, 0]}
  - {name: lid_pos, type: frame_position, entity: lid, frame: lid, target: [0.3, 0, 1.2]}
  - {name: lid_rot, type: frame_orientation, entity: lid, frame: lid}
)";

const char* kSection = R"(trajectories:
  - task: box_pose
    start: 0.5
    carry: [lid_pos]
    waypoints:
      - {at: 2.5, position: [0.3, 0.0, 1.1]}
      - {at: 5.0, position: [0.3, -0.15, 1.1]}
      - {at: 7.0, position: [0.3, -0.15, 0.995]}
)";

scene::Scene buildTestScene() {
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  return scene::buildScene(scene::loadSceneString(kScene, "carry.yaml"), models);
}

std::string errorOf(const std::string& section) {
  const scene::Scene sc = buildTestScene();
  try {
    (void)run::WaypointTrajectory::read(std::string(kScene) + section, "carry.yaml", sc);
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("carry: the minimum-jerk profile and its derivatives", "[carry]") {
  // Boundary values of s = 10τ³ − 15τ⁴ + 6τ⁵: s(0) = 0, s(1) = 1, s' and s'' zero at both ends;
  // s(1/2) = 1/2, s'(1/2) = 15/8 (its largest value).
  CHECK(run::minimumJerk(0.0).norm() == 0.0);
  CHECK(run::minimumJerk(1.0)(0) == Approx(1.0));
  CHECK(std::abs(run::minimumJerk(1.0)(1)) < 1e-12);
  CHECK(std::abs(run::minimumJerk(1.0)(2)) < 1e-12);
  CHECK(run::minimumJerk(0.5)(0) == Approx(0.5));
  CHECK(run::minimumJerk(0.5)(1) == Approx(15.0 / 8.0));
  // s' and s'' against central differences of s and s'.
  const double h = 1e-6;
  for (double tau : {0.1, 0.3, 0.5, 0.77, 0.9}) {
    const double ds = (run::minimumJerk(tau + h)(0) - run::minimumJerk(tau - h)(0)) / (2 * h);
    const double dds = (run::minimumJerk(tau + h)(1) - run::minimumJerk(tau - h)(1)) / (2 * h);
    CHECK(run::minimumJerk(tau)(1) == Approx(ds).margin(1e-7));
    CHECK(run::minimumJerk(tau)(2) == Approx(dds).margin(1e-6));
  }
}

TEST_CASE("carry: the reference passes through the waypoints with consistent derivatives", "[carry]") {
  const scene::Scene sc = buildTestScene();
  const run::WaypointTrajectory tr =
      run::WaypointTrajectory::read(std::string(kScene) + kSection, "carry.yaml", sc);
  REQUIRE(tr.items().size() == 1);
  const run::TrajectorySpec& s = tr.items()[0];
  REQUIRE(s.waypoints.size() == 3);
  // Before the start: the scene's target at rest; on each waypoint: there, at rest.
  CHECK((tr.at(0, 0.2).position - Eigen::Vector3d(0.3, 0, 1.0)).norm() < 1e-12);
  CHECK(tr.at(0, 0.2).velocity.norm() == 0.0);
  for (const run::Waypoint& w : s.waypoints) {
    const run::TrajectoryPoint g = tr.at(0, w.at);
    CHECK((g.position - w.position).norm() < 1e-12);
    CHECK(g.velocity.norm() < 1e-12);
    CHECK(g.acceleration.norm() < 1e-9);
  }
  CHECK((tr.at(0, 9.0).position - s.waypoints.back().position).norm() < 1e-12);
  // Velocity and acceleration against central differences of the position and the velocity,
  // inside each segment.
  const double h = 1e-5;
  for (double t : {0.9, 1.5, 2.2, 3.1, 4.4, 5.5, 6.3, 6.9}) {
    const Eigen::Vector3d v = (tr.at(0, t + h).position - tr.at(0, t - h).position) / (2 * h);
    const Eigen::Vector3d a = (tr.at(0, t + h).velocity - tr.at(0, t - h).velocity) / (2 * h);
    CHECK((tr.at(0, t).velocity - v).norm() < 1e-7);
    CHECK((tr.at(0, t).acceleration - a).norm() < 1e-5);
  }
  // Halfway through the lift: halfway up, at the profile's peak speed 15/8 × 0.1 m / 2 s.
  CHECK(tr.at(0, 1.5).position.z() == Approx(1.05));
  CHECK(tr.at(0, 1.5).velocity.z() == Approx(15.0 / 8.0 * 0.1 / 2.0));
}

TEST_CASE("carry: the box task and the carried task get the references", "[carry]") {
  scene::Scene sc = buildTestScene();
  const run::WaypointTrajectory tr =
      run::WaypointTrajectory::read(std::string(kScene) + kSection, "carry.yaml", sc);
  problem::MultiRobotProblem& p = *sc.problem;
  const int box = sc.task("box_pose"), lid = sc.task("lid_pos");
  const double t = 3.3;
  tr.apply(p, t);
  const run::TrajectoryPoint g = tr.at(0, t);
  const auto& bt = static_cast<const problem::FrameTask&>(p.task(box));
  const auto& lt = static_cast<const problem::FrameTask&>(p.task(lid));
  CHECK((bt.target() - g.position).norm() < 1e-15);
  // The pose task's references: angular rows first, zero; linear rows the trajectory's.
  REQUIRE(p.task(box).referenceRows() == 6);
  CHECK(p.task(box).velocityReference().head<3>().norm() == 0.0);
  CHECK((p.task(box).velocityReference().tail<3>() - g.velocity).norm() < 1e-15);
  CHECK((p.task(box).accelerationReference().tail<3>() - g.acceleration).norm() < 1e-15);
  // The carried task: translated by the box reference's displacement since the start.
  CHECK((lt.target() - (Eigen::Vector3d(0.3, 0, 1.2) + g.position - Eigen::Vector3d(0.3, 0, 1.0))).norm() <
        1e-15);
  CHECK((p.task(lid).velocityReference() - g.velocity).norm() < 1e-15);
}

TEST_CASE("carry: errors of the trajectories section name file, line and field", "[carry]") {
  CHECK(errorOf("trajectories:\n  - {task: nope, waypoints: [{at: 1, position: [0, 0, 1]}]}\n") ==
        "carry.yaml:10: trajectories[0].task: unknown task 'nope' (or not active at the start)");
  CHECK(errorOf("trajectories:\n  - {task: lid_rot, waypoints: [{at: 1, position: [0, 0, 1]}]}\n") ==
        "carry.yaml:10: trajectories[0].task: task 'lid_rot' is a frame_orientation task: expected "
        "frame_position or frame_pose");
  CHECK(
      errorOf("trajectories:\n  - task: box_pose\n    start: 2\n    waypoints:\n"
              "      - {at: 1, position: [0, 0, 1]}\n") ==
      "carry.yaml:13: trajectories[0].waypoints[0].at: expected a time after 2 s (the start or the previous "
      "waypoint)");
  CHECK(errorOf("trajectories:\n  - task: box_pose\n    carry: [box_pose]\n    waypoints:\n"
                "      - {at: 1, position: [0, 0, 1]}\n") ==
        "carry.yaml:11: trajectories[0].carry[0]: task 'box_pose' is already moved by a trajectory");
  CHECK(
      errorOf("trajectories:\n  - {task: box_pose, waypoints: [{at: 1, position: [0, 1]}]}\n") ==
      "carry.yaml:10: trajectories[0].waypoints[0].position: expected a list of 3 numbers, got a list of 2");
  CHECK(errorOf("trajectories:\n  - {task: box_pose, waypoints: []}\n") ==
        "carry.yaml:10: trajectories[0].waypoints: expected at least one waypoint");
  CHECK(
      errorOf("trajectories:\n  - {task: box_pose, speed: 1, waypoints: [{at: 1, position: [0, 0, 1]}]}\n") ==
      "carry.yaml:10: trajectories[0].speed: unknown key");
}
