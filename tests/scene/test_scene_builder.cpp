// Names in a scene file are resolved against the models; a wrong one is reported with the file,
// line and field where it was written, and the list of what exists.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "loop/solution_integrator.hpp"
#include "problem/tasks/frame_position_task.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

void build(const std::string& text) {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  mrqp::scene::buildScene(mrqp::scene::loadSceneString(text, "s.yaml"), models);
}

const char* kArm = "entities:\n  - name: arm\n    model: panda\n";

}  // namespace

TEST_CASE("Scene names are checked against the models", "[scene]") {
  CHECK_THROWS_WITH(build("entities:\n  - name: arm\n    model: pandaa\n"),
                    StartsWith("s.yaml:2: entities[0].model: unknown model 'pandaa'") && Contains("panda"));
  CHECK_THROWS_WITH(build("entities:\n  - name: arm\n    model: panda\n    q: {elbow: 1.0}\n"),
                    StartsWith("s.yaml:2: entities[0].q.elbow: model 'panda' has no joint 'elbow'") &&
                        Contains("panda_joint4"));
  CHECK_THROWS_WITH(build("entities:\n  - name: arm\n    model: panda\n    q: {panda_joint4: 1.0}\n"),
                    StartsWith("s.yaml:2: entities[0].q.panda_joint4: 1 is outside the joint's range"));
  CHECK_THROWS_WITH(
      build(std::string(kArm) +
            "tasks:\n  - name: t\n    type: frame_position\n    entity: arm\n    frame: hand\n"),
      StartsWith("s.yaml:5: tasks[0].frame: entity 'arm' has no frame 'hand'") && Contains("panda_hand_tcp"));
  CHECK_THROWS_WITH(build(std::string(kArm) + "tasks:\n  - name: t\n    type: posture\n    entity: robot\n"),
                    StartsWith("s.yaml:5: tasks[0].entity: unknown entity 'robot' (entities: arm)"));
  CHECK_THROWS_WITH(
      build(std::string(kArm) +
            "contacts:\n  - name: c\n    entity: arm\n    frame: panda_hand\n    other: ground\n"
            "    points: [[0, 0, 0], [0.1, 0, 0]]\n"),
      StartsWith("s.yaml:5: contacts[0]: a surface contact needs at least 3 points"));
}

TEST_CASE("A scene builds with its defaults: targets at the start state", "[scene]") {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  auto scene = mrqp::scene::buildScene(
      mrqp::scene::loadSceneString(std::string(kArm) +
                                       "tasks:\n  - name: reach\n    type: frame_position\n    entity: arm\n"
                                       "    frame: panda_hand_tcp\n",
                                   "s.yaml"),
      models);
  auto& p = *scene.problem;
  const auto& t = dynamic_cast<const mrqp::problem::FramePositionTask&>(p.task(scene.task("reach")));
  CHECK((t.target() - p.entity(0).framePose(t.frame()).p).norm() < 1e-12);
  CHECK(p.entity(0).fullyActuated());
}

TEST_CASE("A joint task follows the critically damped law of eq. 26", "[scene]") {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  auto scene = mrqp::scene::buildScene(
      mrqp::scene::loadSceneString(std::string(kArm) +
                                       "tasks:\n  - name: j\n    type: joint\n    entity: arm\n"
                                       "    joint: panda_joint1\n    stiffness: 4\n    target: 1.0\n",
                                   "s.yaml"),
      models);
  auto& p = *scene.problem;
  const int k = p.entity(0).jointIndex("panda_joint1");
  for (int i = 0; i < 2000; ++i) {
    p.update();
    REQUIRE(p.solve() == mrqp::qp::QpStatus::Optimal);
    mrqp::loop::integrateSolution(p, 0.001);
  }
  // e(t) = −(1 + ωt) e^{−ωt} with ω = 2 at t = 2 s (the same law as the case study's eq. 44).
  CHECK(p.entity(0).q()(k) == Approx(1.0 - 5.0 * std::exp(-4.0)).margin(2e-3));
}

TEST_CASE("Every task type of a scene file becomes the task class of that kind", "[scene]") {
  // One task of each type of the registry, on the Panda and a contact of its hand.
  const std::string text = std::string(kArm) +
                           "contacts:\n  - {name: c, entity: arm, frame: panda_hand_tcp, other: ground, "
                           "points: [[0, 0, 0]], normal: [0, 0, 1]}\n"
                           "tasks:\n"
                           "  - {name: a, type: posture, entity: arm}\n"
                           "  - {name: b, type: com, entity: arm}\n"
                           "  - {name: c, type: frame_position, entity: arm, frame: panda_hand_tcp}\n"
                           "  - {name: d, type: frame_orientation, entity: arm, frame: panda_hand_tcp}\n"
                           "  - {name: e, type: frame_pose, entity: arm, frame: panda_hand_tcp}\n"
                           "  - {name: f, type: joint, entity: arm, joint: panda_joint4}\n"
                           "  - {name: g, type: force, contact: c}\n"
                           "  - {name: h, type: force_min}\n";
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  const auto spec = mrqp::scene::loadSceneString(text, "s.yaml");
  const auto scene = mrqp::scene::buildScene(spec, models);
  REQUIRE(spec.tasks.size() == 8);
  for (const auto& ts : spec.tasks) {
    INFO(ts.name);
    CHECK(std::string(scene.problem->task(scene.task(ts.name)).kind()) == ts.type);
  }
  // At the start every target is the value at the start: no error.
  scene.problem->update();
  for (const auto& ts : spec.tasks) {
    INFO(ts.name);
    CHECK(scene.problem->taskError(scene.task(ts.name)).norm() < 1e-12);
  }
}

TEST_CASE("A task declared inactive is built, left out of the cost and restored on demand", "[scene]") {
  const std::string text = std::string(kArm) +
                           "tasks:\n"
                           "  - {name: reach, type: frame_position, entity: arm, frame: panda_hand_tcp, "
                           "target: [0.3, 0.0, 0.5], weight: 100, active: false}\n";
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  auto scene = mrqp::scene::buildScene(mrqp::scene::loadSceneString(text, "s.yaml"), models);
  auto& p = *scene.problem;
  CHECK(scene.tasks.count("reach") == 0);
  REQUIRE(scene.inactive_tasks.count("reach") == 1);
  const int id = scene.inactive_tasks.at("reach");
  CHECK_FALSE(p.taskActive(id));
  p.update();
  const Eigen::MatrixXd H_off = p.qp().H();  // regularisation only
  CHECK((H_off - 1e-6 * Eigen::MatrixXd::Identity(H_off.rows(), H_off.cols())).norm() < 1e-15);
  REQUIRE(p.restoreTask(id));
  p.update();
  CHECK(p.taskError(id).norm() > 0.01);      // the target is away from the hand
  CHECK((p.qp().H() - H_off).norm() > 1.0);  // the task's 100·JᵀJ is in the cost
}
