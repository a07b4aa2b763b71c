// Bad input for the URDF -> model generator: every malformed file in tests/data/bad_urdf must be
// rejected with a ModelError that names the offending element and the reason. Also the warnings the
// loader returns for valid but unusual models (Romeo, Panda).
//
// Errors found by urdfdom while parsing start with "URDF parse error:" and carry urdfdom's own text,
// which names elements as "joint [j1]" / "Link [b]"; errors found by the generator use "joint 'j1'".
#include <catch2/catch.hpp>

#include <string>

#include "model_files.hpp"
#include "urdf_loader.hpp"

using Catch::Matchers::Contains;
using mrqp::gen::LoadOptions;
using mrqp::gen::ModelError;

namespace {

std::string badFile(const std::string& name) { return std::string(MRQP_TEST_DATA_DIR) + "/bad_urdf/" + name; }
std::string modelFile(const std::string& name) { return mrqp::testing::modelUrdf(name); }

mrqp::gen::KinematicTree loadBad(const std::string& name) {
  return mrqp::gen::loadUrdfFile(badFile(name), {});
}

bool anyWarningHas(const mrqp::gen::KinematicTree& tree, const std::string& a, const std::string& b) {
  for (const auto& w : tree.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

}  // namespace

// The file must be rejected with a ModelError (not another exception type) whose text starts with the
// file path and matches `matcher` (the element name && the reason).
#define REQUIRE_BAD_URDF(file, matcher)                                                          \
  do {                                                                                           \
    REQUIRE_THROWS_AS(loadBad(file), ModelError);                                                \
    REQUIRE_THROWS_WITH(loadBad(file), Catch::Matchers::StartsWith(badFile(file)) && (matcher)); \
  } while (false)

TEST_CASE("bad_urdf: no root link (the joints form a loop)", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("no_root_cycle.urdf", Contains("URDF parse error:") && Contains("joint 'j3'") &&
                                             Contains("closes a kinematic cycle through link 'a'") &&
                                             Contains("no root link"));
}

TEST_CASE("bad_urdf: several root links", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("several_roots.urdf", Contains("URDF parse error:") && Contains("[base]") &&
                                             Contains("[island]") && Contains("Two root links found"));
}

TEST_CASE("bad_urdf: a link with two parent joints", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("two_parents.urdf",
                   Contains("joint 'j3'") && Contains("link 'c' already has parent joint 'j2'"));
}

TEST_CASE("bad_urdf: unknown joint type", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("unknown_joint_type.urdf", Contains("URDF parse error:") && Contains("Joint [j1]") &&
                                                  Contains("no known type [spherical]"));
}

TEST_CASE("bad_urdf: planar joint", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("planar_joint.urdf", Contains("joint 'j1'") && Contains("type planar is not supported"));
}

TEST_CASE("bad_urdf: zero axis on a revolute joint", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("zero_axis.urdf", Contains("joint 'j1'") && Contains("axis is zero"));
}

TEST_CASE("bad_urdf: lower limit above upper limit", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("lower_above_upper.urdf",
                   Contains("joint 'j1'") && Contains("lower limit 1 > upper limit 0"));
}

TEST_CASE("bad_urdf: negative mass", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("negative_mass.urdf", Contains("link 'b'") && Contains("negative mass"));
}

TEST_CASE("bad_urdf: NaN mass", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("nan_mass.urdf",
                   Contains("URDF parse error:") && Contains("Link [b]") && Contains("mass [nan]"));
}

TEST_CASE("bad_urdf: inertia with a negative principal moment", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("inertia_not_psd.urdf",
                   Contains("link 'b'") && Contains("inertia is not positive definite") && Contains("-0.1"));
}

TEST_CASE("bad_urdf: inertia violating the triangle inequality", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("triangle_inequality.urdf", Contains("link 'b'") && Contains("triangle inequality") &&
                                                   Contains("--allow-nonphysical-inertia"));

  SECTION("accepted with a warning when allowed") {
    LoadOptions options;
    options.allow_nonphysical_inertia = true;
    const auto tree = mrqp::gen::loadUrdfFile(badFile("triangle_inequality.urdf"), options);
    CHECK(anyWarningHas(tree, "link 'b'", "triangle inequality"));
  }
}

TEST_CASE("bad_urdf: NaN in a joint origin", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("nan_origin.urdf", Contains("URDF parse error:") && Contains("joint [j1]") &&
                                          Contains("Malformed parent origin") && Contains("[nan]"));
}

TEST_CASE("bad_urdf: infinite inertia component", "[model_gen][bad_urdf]") {
  // urdfdom logs the bad <inertial> but still returns the model (with a zeroed inertial); the loader
  // must not accept it.
  REQUIRE_BAD_URDF("inf_inertia.urdf", Contains("URDF parse error:") && Contains("Link [b]") &&
                                           Contains("inertial") && Contains("ixx"));
}

TEST_CASE("bad_urdf: infinite collision box size", "[model_gen][bad_urdf]") {
  // Same urdfdom behaviour as for the inertial: the collision would silently vanish.
  REQUIRE_BAD_URDF("inf_collision_box.urdf", Contains("URDF parse error:") && Contains("Link [b]") &&
                                                 Contains("collision") && Contains("[inf]"));
}

TEST_CASE("bad_urdf: infinite joint limit", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("inf_limit.urdf", Contains("URDF parse error:") && Contains("joint [j1]") &&
                                         Contains("limit") && Contains("upper value (inf)"));
}

TEST_CASE("bad_urdf: mimic of an unknown joint", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("mimic_unknown.urdf",
                   Contains("joint 'j2'") && Contains("mimic refers to unknown joint 'ghost'"));
}

TEST_CASE("bad_urdf: mimic cycle", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("mimic_cycle.urdf", Contains("joint 'j1'") && Contains("mimic chain forms a cycle"));
}

TEST_CASE("bad_urdf: joint whose child link does not exist", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("missing_child_link.urdf", Contains("URDF parse error:") && Contains("joint [j1]") &&
                                                  Contains("child link [nowhere]") && Contains("not found"));
}

TEST_CASE("bad_urdf: not XML at all", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("not_xml.urdf", Contains("URDF parse error:") && Contains("no <robot> element"));
}

TEST_CASE("bad_urdf: missing file", "[model_gen][bad_urdf]") {
  REQUIRE_BAD_URDF("does_not_exist.urdf", Contains("cannot open file"));
}

TEST_CASE("bad_urdf valid input: romeo loads with nonphysical inertia allowed and warns about massless hands",
          "[model_gen][bad_urdf]") {
  LoadOptions options;
  options.allow_nonphysical_inertia = true;
  mrqp::gen::KinematicTree tree;
  REQUIRE_NOTHROW(tree = mrqp::gen::loadUrdfFile(modelFile("romeo.urdf"), options));
  CHECK(anyWarningHas(tree, "joint 'LHand'", "moves no mass"));
  CHECK(anyWarningHas(tree, "joint 'RHand'", "moves no mass"));
  CHECK(anyWarningHas(tree, "link 'RShoulderYawLink'", "triangle inequality"));
}

TEST_CASE("bad_urdf valid input: romeo without the option fails on the triangle inequality",
          "[model_gen][bad_urdf]") {
  REQUIRE_THROWS_AS(mrqp::gen::loadUrdfFile(modelFile("romeo.urdf"), {}), ModelError);
  REQUIRE_THROWS_WITH(mrqp::gen::loadUrdfFile(modelFile("romeo.urdf"), {}),
                      Contains("link 'RShoulderYawLink'") && Contains("triangle inequality"));
}

TEST_CASE("bad_urdf valid input: panda loads without errors", "[model_gen][bad_urdf]") {
  mrqp::gen::KinematicTree tree;
  REQUIRE_NOTHROW(tree = mrqp::gen::loadUrdfFile(modelFile("panda.urdf"), {}));
  CHECK(tree.nq == 8);
  // Only missing-mesh warnings are expected (the meshes are not shipped with the test data).
  for (const auto& w : tree.warnings) CHECK_THAT(w, Contains("mesh") && Contains("no collision shape"));
}
