// The controller loop on the emulated rig with the ideal plant (docs/loop.md): it reaches the task
// errors of the model run (mrqp-scene's loop: update, solve, integrate on the problem's own
// model), two runs on the simulated buses log the same values, and the robots' joints follow the
// commands through the CAN frames.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "loop/solution_integrator.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

/// mrqp-scene's loop on a scene of its own: the reference the ideal-plant run is compared with.
std::vector<double> modelRunErrors(const std::string& text, const std::string& file, long cycles) {
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  scene::Scene sc = scene::buildScene(scene::loadSceneString(text, file), models);
  auto& p = *sc.problem;
  for (long k = 0; k < cycles; ++k) {
    p.update();
    REQUIRE(p.solve() == qp::QpStatus::Optimal);
    loop::integrateSolution(p, sc.settings.dt);
  }
  p.update();
  std::vector<double> out;
  for (const auto& [name, id] : sc.tasks) out.push_back(p.taskError(id).norm());
  return out;
}

std::vector<double> loopRunErrors(LoopSetup& s, long cycles) {
  for (long k = 0; k < cycles; ++k) s.cycle();
  s.sc.problem->update();
  std::vector<double> out;
  for (const auto& [name, id] : s.sc.tasks) out.push_back(s.sc.problem->taskError(id).norm());
  return out;
}

void compareWithModelRun(const char* file, long cycles, double tracking_bound) {
  const std::string text = looptest::sceneText(file);
  LoopSetup s(text, file);
  REQUIRE(s.boot());
  const std::vector<double> loop = loopRunErrors(s, cycles);
  REQUIRE_FALSE(s.ctrl->safeStopped());
  const std::vector<double> model = modelRunErrors(text, file, cycles);
  REQUIRE(loop.size() == model.size());
  std::size_t i = 0;
  for (const auto& [name, id] : s.sc.tasks) {
    INFO(file << ": task " << name << ": loop " << loop[i] << ", model " << model[i]);
    // The loop sees the robots through 19-bit encoders at 250 Hz (Panda) or 100 Hz (JVRC-1), one
    // robot cycle late, and the objects, mechanisms and floating base through contact kinematics;
    // the model run has its exact state every cycle: the final errors agree to 2 % (or 2e-3
    // absolute for errors that are already small).
    CHECK(std::fabs(loop[i] - model[i]) <= std::max(2e-3, 0.02 * model[i]));
    ++i;
  }
  // The joints followed their commands (to the encoder resolution with the ideal plant).
  for (const loop::RobotIo& r : s.ctrl->robots()) {
    INFO(r.name);
    CHECK(r.tracking_error_max < tracking_bound);
  }
}

}  // namespace

TEST_CASE("loop: panda_door on the emulated drives reaches the model run's task errors", "[loop]") {
  compareWithModelRun("panda_door.yaml", 3000, 1e-4);
}

TEST_CASE("loop: jvrc1_box on the emulated drives reaches the model run's task errors", "[loop]") {
  compareWithModelRun("jvrc1_box.yaml", 1500, 1e-4);
}

TEST_CASE("loop: comanipulation on the emulated drives reaches the model run's task errors", "[loop]") {
  compareWithModelRun("comanipulation.yaml", 1500, 1e-4);
}

TEST_CASE("loop: two runs on the simulated buses log identical values", "[loop]") {
  const std::string text = looptest::sceneText("panda_door.yaml");
  auto run = [&](std::vector<double>* rows, std::vector<std::string>* cols) {
    LoopSetup s(text, "panda_door.yaml");
    loop::LogRing ring;
    s.ctrl->attachLog(ring);
    ring.freeze(4096);
    REQUIRE(s.boot());
    std::vector<double> row(ring.width());
    for (int k = 0; k < 1500; ++k) {
      s.cycle();
      while (ring.pop(row.data())) rows->insert(rows->end(), row.begin(), row.end());
    }
    *cols = ring.columns();
    CHECK(ring.dropped() == 0);
  };
  std::vector<double> a, b;
  std::vector<std::string> cols;
  run(&a, &cols);
  run(&b, &cols);
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() == 1500 * cols.size());
  long compared = 0, differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& c = cols[i % cols.size()];
    if (c.size() > 3 && c.compare(c.size() - 3, 3, "_us") == 0) continue;  // wall-clock timings
    ++compared;
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) ++differing;
  }
  CHECK(compared > 1500 * 20);
  CHECK(differing == 0);
}
