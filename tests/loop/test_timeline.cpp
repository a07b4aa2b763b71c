// The timeline section (docs/loop.md): events resolved against the scene with file/line errors,
// played at their time by the controller's cycle hook.
#include <catch2/catch.hpp>

#include "loop/timeline.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {
std::string errorOf(const std::string& timeline) {
  const std::string text = looptest::sceneText("panda_door.yaml") + "\ntimeline:\n" + timeline;
  LoopSetup s(text, "p.yaml");
  try {
    loop::Timeline::read(text, "p.yaml", s.sc);
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

TEST_CASE("loop: timeline errors name file, line and field", "[loop][timeline]") {
  const int first = lines(looptest::sceneText("panda_door.yaml")) + 3;  // the first event's line
  const std::string at = "p.yaml:" + std::to_string(first) + ": timeline[0]";
  CHECK(errorOf("  - {at: 1, task: lever, weight: 2}\n") == at + ".task: unknown task 'lever'");
  CHECK(errorOf("  - {at: 1, contact: grip_top, active: true}\n") ==
        at + ".active: only 'active: false' (switching off) is supported");
  CHECK(errorOf("  - {at: 1, task: door_angle}\n") ==
        at + ": expected exactly one of 'weight', 'target' and 'active'");
  CHECK(errorOf("  - {at: -1, task: door_angle, weight: 1}\n") == at + ".at: expected a number >= 0, got -1");
}

TEST_CASE("loop: timeline events are played at their time", "[loop][timeline]") {
  const std::string text = looptest::sceneText("panda_door.yaml") +
                           "\ntimeline:\n  - {at: 0.3, contact: grip_top, active: false}\n"
                           "  - {at: 0.1, task: door_angle, weight: 20}\n";
  LoopSetup s(text, "p.yaml");
  loop::Timeline tl = loop::Timeline::read(text, "p.yaml", s.sc);
  REQUIRE(tl.events().size() == 2);
  CHECK(tl.events()[0].at == 0.1);  // time order
  REQUIRE(s.ctrl->addHook(tl));
  REQUIRE(s.boot());
  const int grip = s.sc.contact("grip_top");
  const int task = s.sc.task("door_angle");
  for (int k = 0; k < 400; ++k) {
    const double t = k * s.sc.settings.dt;
    s.cycle();  // the hook ran at time t
    INFO("t = " << t);
    CHECK(s.sc.problem->task(task).weight() == (t >= 0.1 - 1e-9 ? 20.0 : 100.0));
    CHECK(s.sc.problem->contactActive(grip) == (t < 0.3 - 1e-9));
  }
  CHECK(tl.played() == 2);
}
