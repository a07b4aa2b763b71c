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

/// The scene's text with every robot's `state: commanded` replaced by `state: measured`.
std::string measuredState(std::string text) {
  const std::string from = "state: commanded", to = "state: measured";
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

LoopRun runScene(const std::string& file, const std::string& constraint, bool measured) {
  const std::string text = looptest::sceneText(file);
  looptest::LoopSetup s(measured ? measuredState(text) : text, file);
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
    bool measured;  // every robot's state measured (the estimate re-based on the drives' feedback)
  };
  // The plant sits at the drives' targets, rounded to whole encoder increments (2π/524288 rad):
  // measured 6.0 µm below δs for self_collision, 11.8 µm for two_arms, on the plant and on the
  // controller's state alike; 20 µm accepted. two_arms ships with `state: commanded`; run with
  // `state: measured` too, it must end the same: the estimate compares the feedback with the
  // targets as the drives receive them (rounded), so the ideal plant's feedback corrects nothing
  // (before, the correction fed the rounding into the state's velocity and two_arms ended
  // 0.18 mm inside δs: docs/collision.md, "Through the controller loop").
  constexpr double gap = 2e-5;
  for (const Case& k : {Case{"two_arms.yaml", "arms", false}, Case{"two_arms.yaml", "arms", true},
                        Case{"self_collision.yaml", "hand_torso", false}}) {
    INFO(k.file << (k.measured ? " (state: measured)" : ""));
    const LoopRun r = runScene(k.file, k.constraint, k.measured);
    REQUIRE(!r.stopped);
    WARN(k.file << (k.measured ? " (state: measured)" : "") << " through the loop: smallest distance on the plant "
                << r.true_min << " m (" << (r.true_min - r.security) * 1e6
                << " µm from δs), on the controller's estimate " << r.estimate_min << " m");
    CHECK(r.true_min >= r.security - gap);
    CHECK(r.estimate_min >= r.security - gap);
    CHECK(r.true_min <= r.security + 0.01);  // the bodies came close: the constraint stopped them
  }
}
