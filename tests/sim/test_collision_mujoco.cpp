// two_arms (tools/scenes/two_arms.yaml) through the controller loop on the MuJoCo plant of its
// `plant:` section (docs/collision.md, "On the MuJoCo plant"): the arms driven into each other stay
// apart. The distance is measured apart from the constraint, on the plant's true state (every pair
// of the scene's `arms` constraint, exactly, on a second problem of the scene), and the same way on
// the controller's state. The arms' state is their command (the scene's `state: commanded`); the
// plant follows it through the position drives with a lag, and the gap below δs (0.9 mm) is that
// lag: the test bounds it and checks that the controller's state stays at δs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "collision/collision_constraint.hpp"
#include "sim_loop.hpp"

using mrqp::problem::CollisionConstraint;
using mrqp::sim::testing::shippedScene;
using mrqp::sim::testing::SimLoop;

TEST_CASE("MuJoCo loop: two_arms keeps the arms apart on the plant's true state", "[sim][loop][collision]") {
  SimLoop s(shippedScene("two_arms.yaml"), "two_arms.yaml");
  REQUIRE(s.plant_spec.simulator == "mujoco");
  REQUIRE(s.boot());
  auto& p = *s.sc.problem;
  const auto& arms = dynamic_cast<const CollisionConstraint&>(p.constraint(s.sc.constraints.at("arms")));
  const double security = arms.pair(0).security;
  // A second problem of the scene, moved to the plant's state each cycle: the true distance.
  mrqp::scene::Scene shadow = mrqp::scene::buildScene(s.spec, s.models);
  std::vector<int> handles;
  std::vector<Eigen::VectorXd> q, v;
  for (int i = 0; i < p.entityCount(); ++i) {
    handles.push_back(s.plant->entityHandle(p.entity(i).name()));
    REQUIRE(handles.back() >= 0);
    q.emplace_back(p.entity(i).nq());
    v.emplace_back(p.entity(i).nv());
  }
  auto trueDistance = [&]() {
    for (int i = 0; i < p.entityCount(); ++i) {
      const auto ui = static_cast<std::size_t>(i);
      s.plant->entityState(handles[ui], q[ui], v[ui]);
      shadow.problem->entity(i).q() = q[ui];
      shadow.problem->entity(i).v() = v[ui];
      shadow.problem->entity(i).update();
    }
    return arms.measureMinDistance(*shadow.problem);
  };
  const long cycles = std::lround(s.sc.settings.duration / s.sc.settings.dt);
  double true_min = 1e9, estimate_min = 1e9;
  long k = 0;
  for (; k < cycles && !s.ctrl->safeStopped(); ++k) {
    s.cycle();
    true_min = std::min(true_min, trueDistance());
    estimate_min = std::min(estimate_min, arms.measureMinDistance(p));
  }
  INFO("safe stop: " << mrqp::loop::stopReasonStr(s.ctrl->stopReason()));
  REQUIRE(k == cycles);
  CHECK(s.plant->warnings() == 0);
  WARN("two_arms on MuJoCo: smallest true distance " << true_min << " m, on the controller's state "
                                                      << estimate_min << " m (δs " << security << ")");
  // The controller's state stops at δs to the in-process accuracy (20 µm, as on the ideal plant).
  CHECK(estimate_min >= security - 2e-5);
  // The plant within 1.2 mm of δs (measured 0.92 mm inside: the drives' lag, docs/collision.md).
  CHECK(true_min >= security - 0.0012);
  CHECK(true_min <= security + 0.01);  // the arms came close: the constraint stopped them
}
