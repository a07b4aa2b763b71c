// The force_control section of a scene file and the timeline's force-control events
// (control/force/force_control_yaml.hpp): what is read, and bad files reported as
// "FILE:LINE: FIELD: message" with the names that exist.
#include <catch2/catch.hpp>

#include <algorithm>

#include "force/force_control_yaml.hpp"
#include "force_setup.hpp"
#include "loop/timeline.hpp"

using namespace mrqp;

namespace {

/// The test scene without its force_control section.
std::string base() {
  const std::string text = forcetest::dataText("panda_press.yaml");
  return text.substr(0, text.find("force_control:\n"));
}

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

struct Built {
  explicit Built(const std::string& text) {
    scene::addBuiltinModels(models);
    spec = scene::loadSceneString(text, "f.yaml");
    sc = scene::buildScene(spec, models);
    hw = loop::resolveHardware(loop::readHardwareString(text, "f.yaml"), *sc.problem, sc.settings.dt);
  }
  force::ForceControlSpec read(const std::string& text) const {
    return force::readForceControl(text, "f.yaml", sc, hw, sc.settings.dt);
  }
  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene sc;
  loop::ResolvedHardware hw;
};

std::string textOf(const std::string& section, const std::string& timeline = "") {
  return base() + "force_control:\n" + section + (timeline.empty() ? "" : "timeline:\n" + timeline);
}

std::string errorOf(const std::string& section, const std::string& timeline = "") {
  const std::string text = textOf(section, timeline);
  try {
    Built(text).read(text);
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kItem = "{name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], ";

}  // namespace

TEST_CASE("force: the force_control section is read and resolved", "[force][yaml]") {
  const std::string text = forcetest::dataText("panda_press.yaml");
  Built b(text);  // the scene reader accepts the section
  const force::ForceControlSpec fc = b.read(text);
  REQUIRE(fc.present);
  REQUIRE(fc.end_effectors.size() == 1);
  const force::EndEffectorSpec& e = fc.end_effectors[0];
  CHECK(e.name == "tool");
  CHECK(e.entity == b.sc.problem->entityIndex("panda"));
  CHECK(e.task == b.sc.task("press"));
  CHECK(e.sensor_frame == b.sc.problem->entity(e.entity).frameIndex("panda_link8"));
  CHECK(e.sensor == 0);
  CHECK(e.divisor == 4);
  CHECK(e.normal == Eigen::Vector3d(0, 0, -1));
  CHECK(e.normal_in_world);
  CHECK(e.mode == force::ForceMode::Direct);
  CHECK(e.force == 10.0);
  CHECK(e.contact == -1);
  CHECK(e.force_task == -1);
  // Defaults: the paper's gains.
  CHECK(e.gains.gain == 5e-4);
  CHECK(e.gains.v_min == -0.05);
  CHECK(e.gains.v_max == 0.05);
  CHECK(e.gains.cutoff_hz == 20.0);
  CHECK(e.gains.max_displacement == 0.1);
  CHECK(e.tool_mass == 0.0);

  // Every key, and the force task giving the contact.
  const std::string full = textOf(
      "  - {name: tool, entity: panda, task: press, sensor: panda_link8, normal: [0, 0, -2], normal_frame: "
      "task,\n"
      "     mode: qp, force: 12, force_task: press_force, gain: 1.0e-3, velocity_limits: [-0.02, 0.03],\n"
      "     cutoff: 10, tool_mass: 0.7, max_displacement: 0.03}\n",
      "  - {at: 1.0, force_control: tool, mode: autonomous}\n  - {at: 0.5, force_control: tool, force: 4}\n"
      "  - {at: 0.2, task: posture, weight: 2}\n");
  Built f(full);
  const force::ForceControlSpec g = f.read(full);
  const force::EndEffectorSpec& h = g.end_effectors.at(0);
  CHECK(h.normal == Eigen::Vector3d(0, 0, -1));  // normalised
  CHECK_FALSE(h.normal_in_world);
  CHECK(h.mode == force::ForceMode::Qp);
  CHECK(h.force_task == f.sc.task("press_force"));
  CHECK(h.contact == f.sc.contact("hand_table"));
  CHECK(h.gains.gain == 1e-3);
  CHECK(h.gains.v_min == -0.02);
  CHECK(h.gains.v_max == 0.03);
  CHECK(h.gains.cutoff_hz == 10.0);
  CHECK(h.tool_mass == 0.7);
  CHECK(h.gains.max_displacement == 0.03);
  // The timeline's force-control events in time order; the loop's timeline skips them.
  REQUIRE(g.events.size() == 2);
  CHECK(g.events[0].at == 0.5);
  CHECK(g.events[0].set_force);
  CHECK_FALSE(g.events[0].set_mode);
  CHECK(g.events[0].force == 4.0);
  CHECK(g.events[1].mode == force::ForceMode::Autonomous);
  const loop::Timeline tl = loop::Timeline::read(full, "f.yaml", f.sc);
  CHECK(tl.events().size() == 1);
}

TEST_CASE("force: force_control errors name file, line and field", "[force][yaml]") {
  const std::string at = "f.yaml:" + std::to_string(lines(base()) + 2) + ": force_control[0]";
  CHECK(errorOf("  - " + kItem + "mode: direct, force: 1, wieght: 2}\n") == at + ".wieght: unknown key");
  CHECK(errorOf("  - {name: tool, task: press}\n") == at + ": missing required field 'sensor'");
  CHECK(errorOf("  - {name: tool, task: nope, sensor: panda_link8, normal: [0, 0, 1], mode: off}\n") ==
        at + ".task: no frame_position or frame_pose task 'nope' (frame tasks: press)");
  CHECK(errorOf("  - {name: tool, task: posture, sensor: panda_link8, normal: [0, 0, 1], mode: off}\n") ==
        at + ".task: no frame_position or frame_pose task 'posture' (frame tasks: press)");
  CHECK(errorOf("  - {name: tool, task: press, entity: door, sensor: panda_link8, normal: [0, 0, 1], mode: "
                "off}\n") == at + ".entity: task 'press' is on entity 'panda', not 'door'");
  CHECK(
      errorOf("  - {name: tool, task: press, sensor: panda_link7, normal: [0, 0, 1], mode: off}\n") ==
      at + ".sensor: entity 'panda' has no F/T sensor on frame 'panda_link7' (its F/T sensors: panda_link8)");
  CHECK(errorOf("  - " + kItem + "mode: push}\n") ==
        at + ".mode: expected autonomous, direct, qp, guided or off, got \"push\"");
  CHECK(errorOf("  - " + kItem + "mode: direct}\n") ==
        at + ".mode: mode 'direct' uses the user force: give 'force'");
  CHECK(errorOf("  - " + kItem + "mode: autonomous}\n") ==
        at + ".mode: mode 'autonomous' tracks the QP's force on a contact: end-effector 'tool' needs "
             "'contact' (or "
             "'force_task')");
  CHECK(errorOf("  - " + kItem + "mode: qp, force: 5, contact: hand_table}\n") ==
        at + ".mode: mode 'qp' gives the user force to the QP: end-effector 'tool' needs 'force_task' (a "
             "task of "
             "type force)");
  CHECK(errorOf("  - " + kItem + "mode: off, contact: table}\n") ==
        at + ".contact: unknown contact 'table' (contacts: hand_table)");
  CHECK(errorOf("  - " + kItem + "mode: off, force_task: press}\n") ==
        at + ".force_task: no force task 'press' (force tasks: press_force)");
  CHECK(errorOf("  - " + kItem + "mode: off, cutoff: 125}\n") ==
        at + ".cutoff: the cutoff 125 Hz is not below half the rate of robot 'panda' (250 Hz)");
  CHECK(errorOf("  - " + kItem + "mode: off, gain: -1}\n") == at + ".gain: expected a number > 0, got -1");
  CHECK(errorOf("  - " + kItem + "mode: off, max_displacement: 0}\n") ==
        at + ".max_displacement: expected a number > 0, got 0");
  CHECK(errorOf("  - " + kItem + "mode: off, velocity_limits: [0.01, 0.05]}\n") ==
        at + ".velocity_limits: expected [v_min, v_max] with v_min <= 0 <= v_max and v_min < v_max");
  CHECK(errorOf("  - " + kItem + "mode: off, velocity_limits: [0.05]}\n") ==
        at + ".velocity_limits: expected a list of 2 numbers, got a list of 1");
  CHECK(errorOf("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, 0], mode: off}\n") ==
        at + ".normal: expected a non-zero direction");
  CHECK(errorOf("  - " + kItem + "mode: off, normal_frame: hand}\n") ==
        at + ".normal_frame: expected task or world, got \"hand\"");
  CHECK(errorOf("  - " + kItem + "mode: off, tool_mass: -0.1}\n") ==
        at + ".tool_mass: expected a number >= 0, got -0.1");
  CHECK(errorOf("  - " + kItem + "mode: off, force: .nan}\n") ==
        at + ".force: expected a finite number, got .nan");
  // Two end-effectors: distinct names, one admittance per task.
  const std::string second = "f.yaml:" + std::to_string(lines(base()) + 3) + ": force_control[1]";
  CHECK(errorOf("  - " + kItem + "mode: off}\n  - " + kItem + "mode: off}\n") ==
        second + ".name: duplicate end-effector 'tool' (first at line " + std::to_string(lines(base()) + 2) +
            ")");
  CHECK(errorOf("  - " + kItem +
                "mode: off}\n  - {name: other, task: press, sensor: panda_link8, normal: [1, 0, "
                "0], mode: off}\n") ==
        second + ".task: the task already has an admittance (end-effector 'tool', line " +
            std::to_string(lines(base()) + 2) + ")");
  CHECK(errorOf("  - " + kItem + "mode: off}\n") == "(no error)");
}

TEST_CASE("force: timeline force-control events are checked", "[force][yaml]") {
  const std::string item = "  - " + kItem + "mode: direct, force: 10}\n";
  const std::string at = "f.yaml:" + std::to_string(lines(base()) + 4) + ": timeline[0]";
  CHECK(errorOf(item, "  - {at: 1, force_control: hand, mode: direct}\n") ==
        at + ".force_control: unknown end-effector 'hand' (force_control: tool)");
  CHECK(errorOf(item, "  - {at: 1, force_control: tool}\n") == at + ": expected 'mode', 'force' or both");
  CHECK(errorOf(item, "  - {at: 1, force_control: tool, mode: qp}\n") ==
        at + ".mode: mode 'qp' tracks the QP's force on a contact: end-effector 'tool' needs 'contact' (or "
             "'force_task')");
  CHECK(errorOf(item, "  - {at: 1, force_control: tool, force: 5, weight: 2}\n") ==
        at + ".weight: unknown key");
  CHECK(errorOf(item, "  - {at: -1, force_control: tool, force: 5}\n") ==
        at + ".at: expected a number >= 0, got -1");
  // A mode that uses the user force, on an end-effector without one, takes it from the event.
  const std::string none = "  - " + kItem + "mode: off}\n";
  CHECK(errorOf(none, "  - {at: 1, force_control: tool, mode: direct}\n") ==
        at + ".mode: mode 'direct' uses the user force: give 'force'");
  CHECK(errorOf(none, "  - {at: 1, force_control: tool, mode: direct, force: 3}\n") == "(no error)");
  // Without a force_control section an event has no end-effector to name.
  const std::string text = base() + "timeline:\n  - {at: 1, force_control: tool, force: 5}\n";
  Built b(text);
  try {
    b.read(text);
    FAIL("no error");
  } catch (const scene::SceneError& e) {
    CHECK(std::string(e.what()) ==
          "f.yaml:" + std::to_string(lines(base()) + 2) +
              ": timeline[0].force_control: unknown end-effector 'tool' (force_control: none)");
  }
}
