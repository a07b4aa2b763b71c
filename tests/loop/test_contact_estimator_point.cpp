// The contact-kinematics estimate (loop/contact_estimator.hpp) through a contact that leaves every
// rotation free (`free: [twist, tilt]`): it holds a point, the centre of its points, and the fit
// compares that point, not the frame origin. The door's handle frame has its origin on the
// handle's axis; a point 5.5 cm out on the lever, held in the world, fixes both of the door's joints
// (closed form: the configuration at which the contact was recorded), where the frame origin alone
// leaves the handle's angle unobserved.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "loop/contact_estimator.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"

using namespace mrqp;

namespace {

// The lower jaw's contact of panda_door_force on the door's lever, held against the world.
std::string sceneText(const char* free) {
  return std::string(R"(
settings: {dt: 0.001, max_tasks: 2, max_contacts: 2, max_contact_generators: 16}
entities:
  - {name: door, model: door, actuation: none}
contacts:
  - name: held
    entity: door
    frame: handle
    other: ground
    points: [[0.01, -0.03, 0.03], [0.01, -0.05, 0.03], [0.01, -0.05, 0.08], [0.01, -0.03, 0.08]]
    normal: [-1, 0, 0]
)") + free +
         "\n";
}

struct Fixture {
  scene::ModelRegistry models;
  scene::Scene sc;
  explicit Fixture(const char* free) {
    scene::addBuiltinModels(models);
    sc = scene::buildScene(scene::loadSceneString(sceneText(free), "held.yaml"), models);
  }
  problem::Entity& door() { return sc.problem->entity(0); }
};

}  // namespace

TEST_CASE("contact estimate: a contact free in every rotation holds its point on the lever",
          "[loop][estimate]") {
  Fixture f("    free: [twist, tilt]");
  loop::ContactEstimator est(*f.sc.problem, {false}, {-1}, 8);
  problem::Entity& door = f.door();
  door.q().setZero();
  door.v().setZero();
  door.updateKinematics();
  est.estimate();  // records the contact at q = 0: the point's world position is frozen
  REQUIRE(est.estimated(0));

  // The prediction off in both joints (the handle turned by 0.2 rad, the door by 0.05 rad) and
  // moving: the fit brings back the only configuration that puts the point where it was held.
  door.q() << 0.05, -0.2;
  door.v() << 0.1, 0.3;
  door.updateKinematics();
  est.estimate();
  est.estimate();
  CHECK(std::fabs(door.q()(0)) < 1e-7);
  CHECK(std::fabs(door.q()(1)) < 1e-7);
  CHECK(std::fabs(door.v()(0)) < 1e-7);
  CHECK(std::fabs(door.v()(1)) < 1e-7);
}

TEST_CASE("contact estimate: the frame origin on the handle's axis leaves its angle to the prediction",
          "[loop][estimate]") {
  // The same contact free only in tilt about its tangents: its rotation about the normal (the
  // lever's plane) is still held, but the handle's own axis is a tangent, so the position rows at
  // the frame origin, on that axis, do not see the handle's angle: the fit keeps the predicted one.
  // This is what the held point of the first case adds.
  Fixture f("    free: [tilt]");
  loop::ContactEstimator est(*f.sc.problem, {false}, {-1}, 8);
  problem::Entity& door = f.door();
  door.q().setZero();
  door.v().setZero();
  door.updateKinematics();
  est.estimate();
  door.q() << 0.0, -0.2;
  door.updateKinematics();
  est.estimate();
  CHECK(std::fabs(door.q()(0)) < 1e-7);
  CHECK(std::fabs(door.q()(1) + 0.2) < 1e-6);
}
