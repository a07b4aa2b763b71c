// Where models' collision geometry files are found (collision/geometry_path.hpp,
// docs/collision.md "Geometry files"): the built-in files by model name, a user's folders in
// MRQP_COLLISION_GEOMETRY_PATH first, and a scene picking up a user's file for a built-in model.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <string>

#include "collision/collision_constraint.hpp"
#include "collision/geometry_path.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "temp_dir.hpp"

using mrqp::collision::findGeometryFile;
using mrqp::testing::TempDir;

namespace {

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

// Sets MRQP_COLLISION_GEOMETRY_PATH for its lifetime.
struct GeometryPathEnv {
  explicit GeometryPathEnv(const std::string& value) {
    setenv("MRQP_COLLISION_GEOMETRY_PATH", value.c_str(), 1);
  }
  ~GeometryPathEnv() { unsetenv("MRQP_COLLISION_GEOMETRY_PATH"); }
  GeometryPathEnv(const GeometryPathEnv&) = delete;
  GeometryPathEnv& operator=(const GeometryPathEnv&) = delete;
};

}  // namespace

TEST_CASE("collision: geometry files: built-in by model name, a user's folders first", "[collision]") {
  unsetenv("MRQP_COLLISION_GEOMETRY_PATH");
  const std::string builtin = std::string(MRQP_SOURCE_DIR) + "/control/collision/geometry/";
  CHECK(findGeometryFile("panda") == builtin + "panda.yaml");
  CHECK(findGeometryFile("jvrc1") == builtin + "jvrc1.yaml");
  CHECK(findGeometryFile("no_such_model").empty());
  CHECK(findGeometryFile("").empty());

  TempDir a, b;
  writeFile(a.file("panda.yaml"), "links: {}\n");
  writeFile(b.file("my_robot.yaml"), "links: {}\n");
  GeometryPathEnv env(a.path().string() + ":" + b.path().string());
  CHECK(findGeometryFile("panda") == a.file("panda.yaml"));  // the user's own first
  CHECK(findGeometryFile("my_robot") == b.file("my_robot.yaml"));
  CHECK(findGeometryFile("jvrc1") == builtin + "jvrc1.yaml");
  CHECK(findGeometryFile("no_such_model").empty());
}

TEST_CASE("collision: a scene uses a user's geometry file found through MRQP_COLLISION_GEOMETRY_PATH",
          "[collision]") {
  TempDir dir;
  writeFile(dir.file("panda.yaml"),
            "links:\n  panda_hand:\n    - {sphere: 0.1}\n  panda_link7:\n    - {sphere: 0.05}\n");
  GeometryPathEnv env(dir.path().string());
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  const mrqp::scene::Scene s = mrqp::scene::buildScene(mrqp::scene::loadSceneString(R"(
entities:
  - {name: left, model: panda, pose: {xyz: [0, -0.6, 0]}}
  - {name: right, model: panda, pose: {xyz: [0, 0.6, 0]}}
collisions:
  - {name: arms, entities: [left, right]}
)",
                                                                                    "user.yaml"),
                                                       models);
  const auto& c = dynamic_cast<const mrqp::problem::CollisionConstraint&>(
      s.problem->constraint(s.constraints.at("arms")));
  // Two spheres per arm in the user's file (the built-in file has 13 capsules per arm).
  CHECK(c.bodyCount() == 4);
  CHECK(c.pairCount() == 4);
}
