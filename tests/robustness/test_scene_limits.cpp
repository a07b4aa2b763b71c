// Scene files and the YAML reading every configuration file shares, against hostile input
// (control/scene/yaml_reader.hpp, scene_yaml.cpp, problem_settings.hpp; docs/robustness.md):
// yaml-cpp 0.7's LoadAll loop on "[]," is not reached, files are read within a size limit, and
// capacities are refused above their documented maxima with FILE:LINE: FIELD: errors, by the
// reader and by the problem itself.
#include <catch2/catch.hpp>

#include <climits>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bounded_child.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/rigid_object.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

using Catch::Matchers::StartsWith;
using mrqp::scene::SceneError;
using mrqp::testing::ChildEnd;
using mrqp::testing::runBounded;

namespace {

std::string errorOfText(const std::string& text) {
  try {
    mrqp::scene::loadSceneString(text, "mem.yaml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string errorOfFile(const std::string& path) {
  try {
    mrqp::scene::loadSceneFile(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const char* const kEntity = "entities:\n  - {name: box, model: rigid_object, mass: 1, inertia: [1, 1, 1]}\n";

}  // namespace

TEST_CASE("scene: the 4-byte scene '[],' is an error, in bounded memory and time", "[robustness][scene]") {
  // yaml-cpp 0.7's LoadAll would append null documents until the memory is gone.
  CHECK(runBounded([] { return !errorOfText("[],").empty(); }, 256, 10) == ChildEnd::ReturnedTrue);
  CHECK(errorOfText("[],") == "mem.yaml:1: yaml: unexpected ',' after the end of the document");
  CHECK(errorOfText("{},x") == "mem.yaml:1: yaml: unexpected ',' after the end of the document");
  CHECK(errorOfText(std::string(kEntity) + "]") == "mem.yaml:3: yaml: illegal flow end");
  // a real second document still names its line
  CHECK(errorOfText(std::string(kEntity) + "---\nentities: []\n") ==
        "mem.yaml:4: (top level): expected one YAML document, found more than one");
  CHECK(errorOfText(kEntity).empty());
}

TEST_CASE("scene: /dev/zero and files over the size limit are refused", "[robustness][scene]") {
  CHECK(runBounded([] { return !errorOfFile("/dev/zero").empty(); }, 256, 10) == ChildEnd::ReturnedTrue);
  CHECK(errorOfFile("/dev/zero") ==
        "/dev/zero: too large: more than 4194304 bytes, the limit of this kind of file");

  const std::string path = "robustness_size_limit.yaml";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    REQUIRE(f != nullptr);
    const std::string text = std::string(kEntity) + "# padding\n";
    REQUIRE(std::fwrite(text.data(), 1, text.size(), f) == text.size());
    std::fclose(f);
  }
  const std::string text = mrqp::scene::readTextFile(path);
  CHECK(mrqp::scene::readTextFile(path, text.size()) == text);
  try {
    mrqp::scene::readTextFile(path, text.size() - 1);
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()) == path + ": too large: more than " + std::to_string(text.size() - 1) +
                                       " bytes, the limit of this kind of file");
  }
  std::remove(path.c_str());
}

TEST_CASE("scene: capacities above their maxima are FILE:LINE: FIELD: errors", "[robustness][scene]") {
  const auto settings = [](const std::string& line) { return "settings:\n  " + line + "\n" + kEntity; };
  CHECK(errorOfText(settings("max_tasks: 2147483647")) ==
        "mem.yaml:2: settings.max_tasks: expected an integer in [1, 256], got 2147483647");
  CHECK(errorOfText(settings("max_contacts: 2147483647")) ==
        "mem.yaml:2: settings.max_contacts: expected an integer in [1, 64], got 2147483647");
  CHECK(errorOfText(settings("max_contact_generators: 2147483647")) ==
        "mem.yaml:2: settings.max_contact_generators: expected an integer in [1, 1024], got 2147483647");
  CHECK(errorOfText(settings("max_tasks: 99999999999999999999")) ==
        "mem.yaml:2: settings.max_tasks: expected an integer in [1, 256], got 99999999999999999999");
  // the maxima themselves are accepted
  CHECK(errorOfText(
            std::string("settings: {max_tasks: 256, max_contacts: 64, max_contact_generators: 1024}\n") +
            kEntity)
            .empty());

  // CoM dampers need 16 inequality rows each: 255 fit in the 4096 rows with what the other kinds
  // reserve; 257 (4112 rows) cannot, whatever the other kinds reserve.
  const auto dampers = [](int count) {
    std::string s = std::string(kEntity) + "com_dampers:\n";
    for (int i = 0; i < count; ++i) {
      s += "  - {entity: e" + std::to_string(i) + ", interaction: 0.1, security: 0.01, damping: 1}\n";
    }
    return s;
  };
  CHECK(errorOfText(dampers(255)).empty());
  CHECK_THAT(errorOfText(dampers(257)),
             StartsWith("mem.yaml:4: com_dampers: the constraints listed need ") &&
                 Catch::Matchers::EndsWith(" inequality rows, more than the limit of 4096"));
}

TEST_CASE("problem: the capacity guard refuses what the reader would refuse", "[robustness][problem]") {
  using mrqp::problem::capacityError;
  using mrqp::problem::ProblemSettings;
  ProblemSettings s;
  CHECK(capacityError(s) == nullptr);
  const auto with = [](auto set) {
    ProblemSettings t;
    set(t);
    const char* why = capacityError(t);
    return why == nullptr ? std::string() : std::string(why);
  };
  CHECK(with([](ProblemSettings& t) { t.max_tasks = INT_MAX; }) == "max_tasks must be in [0, 256]");
  CHECK(with([](ProblemSettings& t) { t.max_contacts = INT_MAX; }) == "max_contacts must be in [0, 64]");
  CHECK(with([](ProblemSettings& t) { t.max_contact_generators = INT_MAX; }) ==
        "max_contact_generators must be in [0, 1024]");
  CHECK(with([](ProblemSettings& t) { t.max_contacts = -1; }) == "max_contacts must be in [0, 64]");
  // derived rows: 16 per damper + 1 per joint inequality, computed without int overflow
  CHECK(with([](ProblemSettings& t) {
          t.max_com_dampers = 1024;
          t.max_joint_inequalities = 1;
        }) == "constraint slots (max_constraints) must be at most 1024");
  CHECK(with([](ProblemSettings& t) {
          t.max_com_dampers = 257;
          t.max_constraints = 300;
        }) == "constraint rows (max_constraint_rows) must be at most 4096");
  CHECK(with([](ProblemSettings& t) { t.max_constraint_equalities = INT_MAX; }) ==
        "max_constraint_equalities must be at most 1024");
  CHECK(with([](ProblemSettings& t) {
          t.max_tasks = 256;
          t.max_contacts = 64;
          t.max_contact_generators = 1024;
        }).empty());

  // and the problem refuses to be built with them (no signed overflow, no gigabytes)
  ProblemSettings huge;
  huge.max_contact_generators = INT_MAX;
  std::vector<std::unique_ptr<mrqp::problem::Entity>> entities;
  entities.push_back(std::make_unique<mrqp::problem::RigidObject>("box", 1.0, Eigen::Vector3d::Zero(),
                                                                  Eigen::Matrix3d::Identity()));
  CHECK_THROWS_WITH(mrqp::problem::MultiRobotProblem(std::move(entities), huge),
                    "max_contact_generators must be in [0, 1024]");
}
