// The carry measurements of tools/run (carry_watch.hpp) on a scripted plant whose states are
// given in closed form: the waypoint errors, the slip in a hand frame and the drop are known
// exactly, independently of the watch's own arithmetic.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "carry_watch.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "set_state_plant.hpp"
#include "summary_fields.hpp"
#include "temp_dir.hpp"
#include "waypoint_trajectory.hpp"

using namespace mrqp;

namespace {

// A box and a "hand" (a rigid object standing in for a robot's hand) touching it.
const char* kScene = R"(settings: {dt: 0.001, max_tasks: 4}
entities:
  - {name: box, model: rigid_object, mass: 2.0, inertia: [0.05, 0.02, 0.05], pose: {xyz: [0.3, 0, 1.0]}}
  - {name: hand, model: rigid_object, mass: 0.5, inertia: [0.01, 0.01, 0.01], pose: {xyz: [0.3, -0.24, 1.0]}}
contacts:
  - {name: grip, entity: box, frame: box, other: {entity: hand, frame: hand}, points: [[0, -0.24, 0]],
     normal: [0, 1, 0]}
tasks:
  - {name: box_pose, type: frame_pose, entity: box, frame: box, target: [0.3, 0, 1.0, 0, 0, 0]}
)";

const char* kSection = R"(trajectories:
  - task: box_pose
    start: 0.5
    waypoints:
      - {at: 1.0, position: [0.3, 0.0, 1.1]}
      - {at: 2.0, position: [0.3, -0.1, 1.1]}
)";

/// A rigid object's orientation: a yaw angle.
Eigen::Quaterniond yaw(double angle) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())); }

struct Rig {
  Rig() {
    scene::ModelRegistry models;
    scene::addBuiltinModels(models);
    const scene::SceneSpec spec = scene::loadSceneString(kScene, "carry.yaml");
    model = scene::buildScene(spec, models);
    shadow = scene::buildScene(spec, models);
    trajectory = run::WaypointTrajectory::read(std::string(kScene) + kSection, "carry.yaml", model);
  }
  scene::Scene model, shadow;
  run::WaypointTrajectory trajectory;
};

}  // namespace

TEST_CASE("carry: waypoint errors and slip measured on the plant's states", "[carry]") {
  Rig rig;
  mrqp::testing::SetStatePlant plant(*rig.model.problem);
  run::CarryWatch watch(rig.model, *rig.shadow.problem, plant, rig.trajectory, nullptr, 3.0);
  REQUIRE(watch.enabled());
  // The box follows its reference 4 mm low; the hand, turned by 90° about z, holds it until
  // t = 1.5 s, then the box is 20 mm further along the world's x from the hand (in the hand's
  // frame: along its −y, 20 mm).
  const Eigen::Vector3d low(0, 0, -0.004), hand_offset(0, -0.24, 0);
  for (int k = 0; k <= 3000; ++k) {
    const double t = k * 0.001;
    const Eigen::Vector3d box = rig.trajectory.at(0, t).position + low;
    plant.place(0, box, yaw(0.0));
    const Eigen::Vector3d slip = t >= 1.5 ? Eigen::Vector3d(0.02, 0, 0) : Eigen::Vector3d::Zero();
    plant.place(1, box + hand_offset - slip, yaw(std::acos(-1.0) / 2));
    watch.sample(t);
  }
  REQUIRE(watch.waypointErrors().size() == 2);
  CHECK(watch.waypointErrors()[0] == Approx(0.004).epsilon(1e-9));
  CHECK(watch.waypointErrors()[1] == Approx(0.004).epsilon(1e-9));
  CHECK(watch.slip() == Approx(0.02).epsilon(1e-9));
  CHECK_FALSE(watch.dropped());

  // summary.json gets the fields after its own.
  testing::TempDir dir("carry_watch");
  const std::string path = dir.file("summary.json");
  std::ofstream(path) << "{\n  \"scene\": \"x\",\n  \"faults\": []\n}\n";
  REQUIRE(run::appendSummaryFields(path, watch.summaryFields(true)));
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(
      text ==
      "{\n  \"scene\": \"x\",\n  \"faults\": [],\n  \"force_control\": true,\n"
      "  \"box_waypoint_errors_m\": [0.004, 0.004],\n  \"box_slip_m\": 0.02,\n  \"box_dropped\": false\n}\n");
}

TEST_CASE("carry: a box more than 5 cm below its reference is dropped, a waypoint after the run has no error",
          "[carry]") {
  for (const double below : {0.049, 0.051}) {
    Rig rig;
    mrqp::testing::SetStatePlant plant(*rig.model.problem);
    run::CarryWatch watch(rig.model, *rig.shadow.problem, plant, rig.trajectory, nullptr, 1.2);
    for (int k = 0; k <= 1200; ++k) {  // ends before the second waypoint
      const double t = k * 0.001;
      // The box stays on the table while its reference rises 10 cm, then is lifted to `below`
      // under it: it is `below` under the reference from t = 1 s on.
      const double z = std::max(1.0, rig.trajectory.at(0, t).position.z() - below);
      plant.place(0, Eigen::Vector3d(0.3, 0, z), yaw(0.0));
      plant.place(1, Eigen::Vector3d(0.3, -0.24, z), yaw(0.0));
      watch.sample(t);
    }
    CHECK(watch.dropped() == (below > run::CarryWatch::kDropMargin));
    CHECK(watch.waypointErrors()[0] == Approx(below));
    CHECK(std::isnan(watch.waypointErrors()[1]));
    CHECK(watch.slip() == 0.0);
  }
}
