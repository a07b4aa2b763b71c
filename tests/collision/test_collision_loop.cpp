// The shipped collision scenes through the controller loop as mrqp-run runs them with the ideal
// plant (tests/loop/loop_setup.hpp: the emulated CiA 402 drives on the simulated buses, the
// controller's state estimate re-based on their feedback each robot cycle): the bodies stop at δs
// on the plant's true state. The distance is measured apart from the constraint: every pair of the
// scene's constraint, exactly, on a second problem of the scene moved to the plant's state after
// every cycle (as mrqp-run's summary.json min_distance_m).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "collision/collision_constraint.hpp"
#include "loop_setup.hpp"

using mrqp::problem::CollisionConstraint;

namespace {

struct LoopRun {
  double true_min = 1e9;      ///< smallest distance on the plant's state
  double estimate_min = 1e9;  ///< smallest distance on the controller's own state
  double security = 0.0;
  bool stopped = false;
};

LoopRun runScene(const std::string& file, const std::string& constraint) {
  looptest::LoopSetup s(looptest::sceneText(file), file);
  REQUIRE(s.boot());
  auto& p = *s.sc.problem;
  const auto& c = dynamic_cast<const CollisionConstraint&>(p.constraint(s.sc.constraints.at(constraint)));
  mrqp::scene::Scene shadow = mrqp::scene::buildScene(s.spec, s.models);
  std::vector<Eigen::VectorXd> q, v;
  for (int i = 0; i < p.entityCount(); ++i) {
    q.emplace_back(p.entity(i).nq());
    v.emplace_back(p.entity(i).nv());
  }
  LoopRun r;
  r.security = c.pair(0).security;
  const long cycles = std::lround(s.sc.settings.duration / s.sc.settings.dt);
  for (long k = 0; k < cycles && !s.ctrl->safeStopped(); ++k) {
    s.cycle();
    for (int i = 0; i < p.entityCount(); ++i) {
      const auto ui = static_cast<std::size_t>(i);
      s.plant->entityState(i, q[ui], v[ui]);
      shadow.problem->entity(i).q() = q[ui];
      shadow.problem->entity(i).v() = v[ui];
      shadow.problem->entity(i).update();
    }
    r.true_min = std::min(r.true_min, c.measureMinDistance(*shadow.problem));
    r.estimate_min = std::min(r.estimate_min, c.measureMinDistance(p));
  }
  r.stopped = s.ctrl->safeStopped();
  return r;
}

}  // namespace

TEST_CASE("collision: the shipped scenes stop at δs through the controller loop (ideal plant)",
          "[collision][loop]") {
  struct Case {
    const char* file;
    const char* constraint;
    double gap;  // accepted distance below δs, on the plant and on the controller's state
  };
  // self_collision: a few µm (the plant sits at the drives' targets, rounded to whole encoder
  // increments: measured 6.0 µm below δs). two_arms: 0.18 mm measured below δs, on the plant and
  // on the controller's state alike: the estimate's velocity correction compares the CSP drives'
  // velocity, derived from two successive rounded targets, with one derived from the unrounded
  // positions, and feeds the rounding (up to 3 mrad/s per joint) into the state each robot cycle
  // (docs/collision.md, "Through the controller loop"); 0.25 mm accepted.
  for (const Case& k : {Case{"two_arms.yaml", "arms", 2.5e-4}, Case{"self_collision.yaml", "hand_torso", 2e-5}}) {
    INFO(k.file);
    const LoopRun r = runScene(k.file, k.constraint);
    REQUIRE(!r.stopped);
    WARN(k.file << " through the loop: smallest distance on the plant " << r.true_min << " m ("
                << (r.true_min - r.security) * 1e6 << " µm from δs), on the controller's estimate "
                << r.estimate_min << " m");
    CHECK(r.true_min >= r.security - k.gap);
    CHECK(r.estimate_min >= r.security - k.gap);
    CHECK(r.true_min <= r.security + 0.01);  // the bodies came close: the constraint stopped them
  }
}
