// --set KEY=VALUE on a scene file (docs/loop.md): a value replaced in place keeps every line of
// the file; paths by index and by item name; errors name file, line and path.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>
#include "loop/scene_override.hpp"

#include "scene/scene_yaml.hpp"

using mrqp::loop::applySceneOverride;

namespace {
const char* kText =
    "settings: {dt: 0.001, duration: 4.0}\n"  // 1
    "tasks:\n"                                // 2
    "  - name: door_angle\n"                  // 3
    "    weight: 100\n"                       // 4
    "    target: [-0.25]\n"                   // 5
    "  - name: posture\n"                     // 6
    "    weight: 0.1   # small\n";            // 7

std::string errorOf(const std::string& assignment) {
  try {
    applySceneOverride(kText, "s.yaml", assignment);
  } catch (const mrqp::scene::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("loop: --set replaces one value in place", "[loop][set]") {
  CHECK(applySceneOverride(kText, "s.yaml", "settings.duration=2") ==
        std::string(kText).replace(std::string(kText).find("4.0"), 3, "2"));
  const std::string by_name = applySceneOverride(kText, "s.yaml", "tasks[door_angle].target=[-0.4]");
  CHECK(by_name.find("    target: [-0.4]\n") != std::string::npos);
  CHECK(by_name.find("[-0.25]") == std::string::npos);
  const std::string by_index = applySceneOverride(kText, "s.yaml", "tasks[1].weight=5");
  CHECK(by_index.find("    weight: 5   # small\n") != std::string::npos);
  CHECK(std::count(by_index.begin(), by_index.end(), '\n') == 7);
}

TEST_CASE("loop: --set adds a key the file does not have", "[loop][set]") {
  const std::string out = applySceneOverride(kText, "s.yaml", "tasks[door_angle].stiffness=4");
  const YAML::Node doc = YAML::Load(out);
  CHECK(doc["tasks"][0]["stiffness"].as<double>() == 4.0);
  CHECK(doc["tasks"][0]["weight"].as<double>() == 100.0);  // the rest unchanged
  CHECK(doc["tasks"][1]["name"].as<std::string>() == "posture");
  CHECK(doc["settings"]["duration"].as<double>() == 4.0);
}

TEST_CASE("loop: --set errors name file, line and path", "[loop][set]") {
  CHECK(errorOf("tasks[7].weight=1") == "s.yaml:3: tasks: --set: no item [7] (the list has 2)");
  CHECK(errorOf("tasks[door].weight=1") == "s.yaml:3: tasks: --set: no item [door] (the list has 2)");
  CHECK(errorOf("tasks[0].colour.x=1") == "s.yaml:3: tasks[0].colour: --set: no such key");
  CHECK(errorOf("settings") == "s.yaml:1: settings: --set: expected KEY=VALUE");
}
