// The limits of the URDF loader (model_gen/src/generator_limits.hpp) and the numeric checks of what it
// reads: each input recreated here, each refused with an error naming the file, the element and the
// limit, or (under a limit) accepted without recursion on its size.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "code_emitter.hpp"
#include "generator_limits.hpp"
#include "parent_walk.hpp"
#include "temp_dir.hpp"
#include "urdf_loader.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using mrqp::gen::KinematicTree;
using mrqp::gen::LoadOptions;
using mrqp::gen::ModelError;

namespace {

KinematicTree load(const std::string& xml) { return mrqp::gen::loadUrdfString(xml, "inline.urdf", ".", {}); }

std::string loadError(const std::string& xml) {
  try {
    load(xml);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(accepted)";
}

const char* kInertial =
    "<inertial><mass value='1'/><inertia ixx='0.1' ixy='0' ixz='0' iyy='0.1' iyz='0' izz='0.1'/></inertial>";

/// A chain of n links l0 .. l(n-1), each 0.01 m above its parent, joined by revolute joints about y.
/// Names are numbered so that the root sorts first (urdfdom's link map then releases the chain from
/// its leaf: the order that once recursed).
std::string chain(std::size_t n) {
  std::string s = "<robot name='chain'>";
  char buf[320];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "<link name='l%06zu'>%s</link>\n", i, kInertial);
    s += buf;
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    std::snprintf(buf, sizeof buf,
                  "<joint name='j%06zu' type='revolute'><parent link='l%06zu'/><child link='l%06zu'/>"
                  "<origin xyz='0 0 0.01'/><axis xyz='0 1 0'/>"
                  "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n",
                  i, i, i + 1);
    s += buf;
  }
  return s + "</robot>\n";
}

/// A one-joint robot with `joint_extra` inside the joint and `link_extra` inside the child link.
std::string oneJoint(const std::string& joint_extra, const std::string& link_extra = kInertial,
                     const std::string& type = "revolute") {
  return "<robot name='r'><link name='a'/><link name='b'>" + link_extra + "</link><joint name='j' type='" +
         type + "'><parent link='a'/><child link='b'/>" + joint_extra + "</joint></robot>";
}

const std::string kLimit = "<limit lower='-1' upper='1' effort='1' velocity='1'/>";

using mrqp::testing::TempDir;

}  // namespace

TEST_CASE("limits: 100,000 nested XML elements are refused before urdfdom parses", "[model_gen][limits]") {
  const std::size_t n = 100000;
  std::string xml = "<robot name='r'><link name='a'/>";
  for (std::size_t i = 0; i < n; ++i) xml += "<x>";
  for (std::size_t i = 0; i < n; ++i) xml += "</x>";
  xml += "</robot>";
  CHECK_THAT(loadError(xml), StartsWith("inline.urdf: ") && Contains("<x> nested deeper than 64 levels") &&
                                 Contains("at line 1"));

  // the limit itself: <robot> is level 1, so 63 levels inside it are accepted, 64 are not
  auto nested = [](int levels) {
    std::string s = "<robot name='r'><link name='a'/>";
    for (int i = 0; i < levels; ++i) s += "<x>";
    for (int i = 0; i < levels; ++i) s += "</x>";
    return s + "</robot>";
  };
  CHECK(loadError(nested(mrqp::gen::kMaxUrdfDepth - 1)) == "(accepted)");
  CHECK_THAT(loadError(nested(mrqp::gen::kMaxUrdfDepth)), Contains("nested deeper than 64 levels"));
}

TEST_CASE("limits: long chains are walked without recursion up to the link limit, refused above",
          "[model_gen][limits]") {
  SECTION("7,000 links: loaded and generated") {
    const KinematicTree t = load(chain(7000));
    REQUIRE(t.bodies.size() == 7000);
    CHECK(t.nv == 6999);
    bool parents = true, placed = true;
    for (std::size_t b = 1; b < t.bodies.size(); ++b) {
      parents = parents && t.bodies[b].parent == static_cast<int>(b) - 1 &&
                t.bodies[b].name == t.frames[b].name && t.frames[b].body == static_cast<int>(b);
      placed = placed && t.bodies[b].p0.z() == 0.01;
    }
    CHECK(parents);
    CHECK(placed);
    const auto code = mrqp::gen::emitModel(t, "chain7000", "chain.urdf", false);
    CHECK_THAT(code.header, Contains("inline constexpr int nbodies = 7000;"));
  }
  SECTION("10,000 links (the limit): loaded") {
    CHECK(load(chain(mrqp::gen::kMaxLinks)).bodies.size() == 10000);
  }
  SECTION("10,001 and 20,000 links: the link limit") {
    CHECK_THAT(
        loadError(chain(mrqp::gen::kMaxLinks + 1)),
        Contains("<link name='l010000'>: more than 10000 <link> elements (the link limit) at line 10001"));
    CHECK_THAT(loadError(chain(20000)), Contains("more than 10000 <link> elements"));
  }
  SECTION("more joints than the joint limit") {
    std::string xml = "<robot name='r'><link name='a'/>";
    for (std::size_t i = 0; i <= mrqp::gen::kMaxJoints; ++i)
      xml += "<joint name='j" + std::to_string(i) +
             "' type='fixed'><parent link='a'/><child link='a'/></joint>\n";
    CHECK_THAT(
        loadError(xml + "</robot>"),
        Contains("<joint name='j10000'>: more than 10000 <joint> elements (the joint limit) at line 10001"));
  }
}

TEST_CASE("limits: the cycle check follows each parent link at most twice", "[model_gen][limits]") {
  using mrqp::gen::firstNodeOnCycle;
  const int n = 1000000;
  std::size_t steps = 0;
  // a chain listed leaf first: the order in which walking up from every node separately is quadratic
  std::vector<int> parent(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) parent[static_cast<std::size_t>(i)] = i + 1 < n ? i + 1 : -1;
  CHECK(firstNodeOnCycle(parent, &steps) == -1);
  CHECK(steps <= 2 * static_cast<std::size_t>(n));
  // the same chain whose root points back at the leaf: a cycle through every node
  parent.back() = 0;
  CHECK(firstNodeOnCycle(parent, &steps) == 0);
  CHECK(steps <= 2 * static_cast<std::size_t>(n));
  // a tree (a root, a chain below it) and a separate 3-cycle hanging a 10-node tail
  std::vector<int> p = {-1, 0, 1, 2, 5, 6, 4};  // 4 -> 5 -> 6 -> 4
  for (int i = 0; i < 10; ++i) p.push_back(i == 0 ? 6 : static_cast<int>(p.size()) - 1);
  CHECK(firstNodeOnCycle(p, &steps) == 4);
  CHECK(steps <= 2 * p.size());
}

TEST_CASE("limits: a kinematic cycle beside a long chain is found and named", "[model_gen][limits]") {
  std::string xml = chain(9000);
  xml.erase(xml.rfind("</robot>"));
  xml += std::string("<link name='ca'>") + kInertial + "</link><link name='cb'>" + kInertial +
         "</link><link name='cc'>" + kInertial + "</link>" +
         "<joint name='c1' type='fixed'><parent link='ca'/><child link='cb'/></joint>"
         "<joint name='c2' type='fixed'><parent link='cb'/><child link='cc'/></joint>"
         "<joint name='c3' type='fixed'><parent link='cc'/><child link='ca'/></joint></robot>";
  CHECK_THAT(loadError(xml), Contains("joint 'c3': closes a kinematic cycle through link 'ca'"));
}

TEST_CASE("limits: a joint axis is normalised without overflow, NaN and infinite axes are refused",
          "[model_gen][limits]") {
  const KinematicTree t = load(oneJoint("<axis xyz='1e300 1e300 1e300'/>" + kLimit));
  REQUIRE(t.bodies.size() == 2);
  const Eigen::Vector3d expected = Eigen::Vector3d::Ones() / std::sqrt(3.0);
  CHECK((t.bodies[1].joint.axis - expected).cwiseAbs().maxCoeff() < 1e-15);
  const KinematicTree tiny = load(oneJoint("<axis xyz='0 -3e-11 0'/>" + kLimit));
  CHECK(tiny.bodies[1].joint.axis == Eigen::Vector3d(0, -1, 0));
  const KinematicTree big = load(oneJoint("<axis xyz='1e308 -1e308 0'/>" + kLimit, kInertial, "prismatic"));
  CHECK((big.bodies[1].joint.axis - Eigen::Vector3d(1, -1, 0) / std::sqrt(2.0)).cwiseAbs().maxCoeff() <
        1e-15);

  CHECK_THAT(loadError(oneJoint("<axis xyz='nan 0 1'/>" + kLimit)), Contains("joint") && Contains("nan"));
  CHECK_THAT(loadError(oneJoint("<axis xyz='0 inf 1'/>" + kLimit)), Contains("joint") && Contains("inf"));
  CHECK_THAT(loadError(oneJoint("<axis xyz='0 0 1e-13'/>" + kLimit)), Contains("joint 'j': axis is zero"));
}

TEST_CASE("limits: numbers outside their range are refused naming element and field", "[model_gen][limits]") {
  CHECK_THAT(loadError(oneJoint(kLimit,
                                "<inertial><mass value='1e7'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' "
                                "iyz='0' izz='1'/></inertial>")),
             Contains("link 'b' inertial: mass 1e+07 is outside [-1e+06, 1e+06]"));
  CHECK_THAT(loadError(oneJoint(kLimit,
                                "<inertial><mass value='1'/><inertia ixx='1e300' ixy='0' ixz='0' "
                                "iyy='1e300' iyz='0' izz='1e300'/></inertial>")),
             Contains("link 'b' inertial: ixx 1e+300 is outside"));
  CHECK_THAT(loadError(oneJoint("<origin xyz='0 0 1e300'/>" + kLimit)),
             Contains("joint 'j' origin: z 1e+300 is outside [-10000, 10000]"));
  CHECK_THAT(loadError(oneJoint("<limit lower='-1' upper='1' effort='1e300' velocity='1'/>")),
             Contains("joint 'j' limit: effort 1e+300 is outside"));
  CHECK_THAT(loadError("<robot name='r'><link name='a'><collision><geometry><box size='1 1e6 1'/></geometry>"
                       "</collision></link></robot>"),
             Contains("link 'a' collision: box size y 1e+06 is outside"));
  CHECK_THAT(loadError("<robot name='r'><link name='a'><collision><origin xyz='2e4 0 0'/><geometry><sphere "
                       "radius='1'/></geometry></collision></link></robot>"),
             Contains("link 'a' collision origin: x 20000 is outside"));
  const std::string mimic =
      "<robot name='r'><link name='a'/><link name='b'/><link name='c'/>"
      "<joint name='j1' type='continuous'><parent link='a'/><child link='b'/></joint>"
      "<joint name='j2' type='continuous'><parent link='b'/><child link='c'/>"
      "<mimic joint='j1' multiplier='1e300'/></joint></robot>";
  CHECK_THAT(loadError(mimic), Contains("joint 'j2' mimic: multiplier 1e+300 is outside [-1e+06, 1e+06]"));

  // meshes: the scale, and the vertices once scaled (tests/data/meshes/cube.obj spans [0, 1])
  auto meshError = [](const std::string& scale) {
    try {
      mrqp::gen::loadUrdfString(
          "<robot name='r'><link name='a'><collision><geometry><mesh filename='cube.obj' "
          "scale='" +
              scale + "'/></geometry></collision></link></robot>",
          "inline.urdf", std::string(MRQP_TEST_DATA_DIR) + "/meshes", {});
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK(meshError("5000 1 1") == "(accepted)");
  CHECK_THAT(meshError("1 1e300 1"),
             Contains("link 'a' collision: mesh scale y 1e+300 is outside [-1e+06, 1e+06]"));
  CHECK_THAT(meshError("1 1 2e4"), Contains("link 'a' collision: mesh 'cube.obj': a vertex at (") &&
                                       Contains("after scale is outside [-10000, 10000]"));
}

TEST_CASE("limits: a URDF over the size limit is refused from its size, devices are not read",
          "[model_gen][limits]") {
  TempDir dir;
  const std::string big = dir.file("huge.urdf");
  { std::ofstream(big) << "<robot name='r'><link name='a'/></robot>"; }
  fs::resize_file(big, std::uintmax_t{1} << 40);  // 1 TiB, sparse: reading it would not end
  CHECK_THROWS_WITH(mrqp::gen::loadUrdfFile(big, {}),
                    StartsWith(big + ": larger than the 33554432-byte URDF limit (1099511627776 bytes)"));
  fs::resize_file(big, mrqp::gen::kMaxUrdfBytes + 1);
  CHECK_THROWS_WITH(mrqp::gen::loadUrdfFile(big, {}), Contains("larger than the 33554432-byte URDF limit"));
  CHECK_THROWS_WITH(mrqp::gen::loadUrdfFile("/dev/zero", {}),
                    StartsWith("/dev/zero: cannot open file: not a regular file"));
  const std::string text(mrqp::gen::kMaxUrdfBytes + 1, ' ');
  CHECK_THROWS_WITH(mrqp::gen::loadUrdfString(text, "stream", ".", {}),
                    StartsWith("stream: larger than the 33554432-byte URDF limit"));
}

TEST_CASE("limits: collision elements and mimic chains", "[model_gen][limits]") {
  auto collisions = [](std::size_t n) {
    std::string s = "<robot name='r'><link name='a'>";
    for (std::size_t i = 0; i < n; ++i)
      s += "<collision><geometry><sphere radius='0.1'/></geometry></collision>\n";
    return s + "</link></robot>";
  };
  CHECK(load(collisions(mrqp::gen::kMaxCollisions)).shapes.size() == mrqp::gen::kMaxCollisions);
  CHECK_THAT(
      loadError(collisions(mrqp::gen::kMaxCollisions + 1)),
      Contains("<link name='a'>: more than 10000 <collision> elements in the robot (the collision limit) at "
               "line 10001"));

  // joints j0 .. j(n-1) in a chain, each mimicking the next one, j(n-1) independent: resolving j0
  // walks the whole chain (a mimic of a joint earlier in the tree is resolved through it at once)
  auto mimics = [](std::size_t n) {
    std::string s = "<robot name='r'><link name='l0'/>";
    for (std::size_t i = 0; i < n; ++i) {
      const std::string k = std::to_string(i);
      s += "<link name='l" + std::to_string(i + 1) + "'/><joint name='j" + k +
           "' type='continuous'><parent link='l" + k + "'/><child link='l" + std::to_string(i + 1) + "'/>" +
           (i + 1 < n ? "<mimic joint='j" + std::to_string(i + 1) + "' multiplier='1'/>" : "") + "</joint>";
    }
    return s + "</robot>";
  };
  const KinematicTree t = load(mimics(mrqp::gen::kMaxMimicChain));
  CHECK(t.nv == 1);
  CHECK(t.bodies[1].joint.mimicked == "j63");
  CHECK_THAT(loadError(mimics(mrqp::gen::kMaxMimicChain + 1)),
             Contains("joint 'j0': mimic chain longer than 64 joints (the mimic chain limit)"));
}
