// PenClickWatch (tools/run/pen_click_watch.hpp) on states set by hand: the button's travel is the
// plant's joint value, the required travel the stop of pen.urdf (6 mm) less 0.1 mm, the slip the
// length of a displacement of the pen in the world with the hand still, and zero when the pen
// moves rigidly with the palm (the hand's wrist turned, the pen carried along).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "pen_click_watch.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "set_state_plant.hpp"

using namespace mrqp;

namespace {

const std::string kScene = std::string(MRQP_SCENES_DIR) + "/pen_click.yaml";

}  // namespace

TEST_CASE("PenClickWatch: travel, required travel and slip of the pen in the palm", "[scene_pen]") {
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  const scene::SceneSpec spec = scene::loadSceneFile(kScene);
  scene::Scene sc = scene::buildScene(spec, models);
  problem::MultiRobotProblem& p = *sc.problem;
  const int hand = p.entityIndex("hand");
  const int pen = p.entityIndex("pen");
  REQUIRE(hand >= 0);
  REQUIRE(pen >= 0);

  mrqp::testing::SetStatePlant plant;
  plant.add("hand", p.entity(hand).q());
  plant.add("pen", p.entity(pen).q());
  run::PenClickWatch watch(spec, models, p, plant, 10);
  REQUIRE(watch.enabled());
  CHECK(watch.travelRequired() == Approx(0.006 - 1e-4).margin(1e-15));

  watch.measure(0.0);
  CHECK(watch.slipMax() == Approx(0.0).margin(1e-15));
  CHECK(watch.travelMax() == Approx(0.0).margin(1e-15));

  // The pen displaced in the world by d, its button pressed 4 mm, the hand still: slip |d|.
  const Eigen::Vector3d d(0.001, -0.002, 0.0005);
  plant.q(1).head<3>() += d;
  plant.q(1)(7) = 0.004;
  watch.measure(0.001);
  CHECK(watch.slipMax() == Approx(d.norm()).epsilon(1e-12));
  CHECK(watch.travelMax() == Approx(0.004).epsilon(1e-12));

  // Back, the button at 2 mm: the maxima stay.
  plant.q(1) = p.entity(pen).q();
  plant.q(1)(7) = 0.002;
  watch.measure(0.002);
  CHECK(watch.slipMax() == Approx(d.norm()).epsilon(1e-12));
  CHECK(watch.travelMax() == Approx(0.004).epsilon(1e-12));

  // The wrist turned by 0.3 rad and the pen carried along rigidly with the palm: no new slip.
  problem::Entity& h = p.entity(hand);
  problem::Entity& e = p.entity(pen);
  h.update();
  e.update();
  const int palm = h.frameIndex("palm");
  const problem::Pose palm0 = h.framePose(palm);
  const problem::Pose pen0 = e.framePose(0);
  const int wrj1 = h.qIndexOfV(h.jointIndex("WRJ1"));
  h.q()(wrj1) += 0.3;
  h.update();
  const problem::Pose palm1 = h.framePose(palm);
  const Eigen::Matrix3d R = palm1.R * palm0.R.transpose();
  const Eigen::Vector3d pen_p = R * (pen0.p - palm0.p) + palm1.p;
  const Eigen::Quaterniond pen_quat(R * pen0.R);
  plant.q(0) = h.q();
  plant.q(1).head<3>() = pen_p;
  plant.q(1)(3) = pen_quat.w();
  plant.q(1)(4) = pen_quat.x();
  plant.q(1)(5) = pen_quat.y();
  plant.q(1)(6) = pen_quat.z();
  plant.q(1)(7) = 0.001;
  watch.measure(0.003);
  CHECK(watch.slipMax() == Approx(d.norm()).epsilon(1e-12));
  CHECK((pen_p - pen0.p).norm() > 0.01);  // the pen did move in the world

  const auto fields = watch.summaryFields();
  REQUIRE(fields.size() == 3);
  CHECK(fields[0].first == "button_travel_max_m");
  CHECK(fields[1].first == "button_travel_required_m");
  CHECK(fields[2].first == "pen_slip_m");
}

TEST_CASE("PenClickWatch: a scene without a pen measures nothing", "[scene_pen]") {
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  const scene::SceneSpec spec = scene::loadSceneFile(std::string(MRQP_SCENES_DIR) + "/panda_door.yaml");
  scene::Scene sc = scene::buildScene(spec, models);
  mrqp::testing::SetStatePlant plant;
  run::PenClickWatch watch(spec, models, *sc.problem, plant, 10);
  CHECK_FALSE(watch.enabled());
  watch.measure(0.0);
  CHECK(watch.summaryFields().empty());
}
