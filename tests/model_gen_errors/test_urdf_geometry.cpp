// Collision geometry and merged frames as the loader builds them from URDF text.
#include <catch2/catch.hpp>

#include <string>

#include "urdf_loader.hpp"

using mrqp::gen::KinematicTree;
using mrqp::gen::LoadOptions;
using mrqp::gen::ShapeKind;

namespace {

const std::string kMeshDir = std::string(MRQP_TEST_DATA_DIR) + "/meshes";

KinematicTree load(const std::string& links) {
  const std::string xml = "<robot name='t'>" + links + "</robot>";
  return mrqp::gen::loadUrdfString(xml, "inline.urdf", kMeshDir, LoadOptions{});
}

}  // namespace

TEST_CASE("a readable mesh becomes the convex hull of its vertices, scaled", "[model_gen]") {
  // cube.obj: a unit cube (8 corners) plus points inside it
  const KinematicTree t = load(
      "<link name='a'><collision><origin xyz='0 0 1'/><geometry><mesh filename='cube.obj' scale='2 2 2'/>"
      "</geometry></collision></link>");
  REQUIRE(t.shapes.size() == 1);
  CHECK(t.shapes[0].kind == ShapeKind::ConvexMesh);
  CHECK(t.shapes[0].vertices.size() == 8);
  for (const auto& v : t.shapes[0].vertices) CHECK(v.cwiseAbs().maxCoeff() <= 2.0 + 1e-12);
  CHECK(t.shapes[0].p.z() == Approx(1.0));
}

TEST_CASE("an unreadable mesh gives a named warning and no shape; primitives are kept", "[model_gen]") {
  const KinematicTree t = load(
      "<link name='a'><collision><geometry><mesh filename='package://nowhere/x.stl'/></geometry></collision>"
      "<collision><geometry><box size='1 2 3'/></geometry></collision></link>"
      "<link name='b'><collision><geometry><cylinder radius='0.1' "
      "length='0.5'/></geometry></collision></link>"
      "<joint name='j' type='fixed'><parent link='a'/><child link='b'/><origin xyz='0 0 2'/></joint>");
  REQUIRE(t.shapes.size() == 2);
  CHECK(t.shapes[0].kind == ShapeKind::Box);
  CHECK(t.shapes[0].size.y() == Approx(2.0));
  // link b is merged into a's body by the fixed joint: its cylinder sits 2 m up on body 0
  CHECK(t.shapes[1].kind == ShapeKind::Cylinder);
  CHECK(t.shapes[1].body == 0);
  CHECK(t.shapes[1].p.z() == Approx(2.0));
  bool warned = false;
  for (const auto& w : t.warnings)
    if (w.find("link 'a'") != std::string::npos && w.find("x.stl") != std::string::npos) warned = true;
  CHECK(warned);
  REQUIRE(t.frames.size() == 2);
  CHECK(t.frames[1].name == "b");
  CHECK(t.frames[1].p.z() == Approx(2.0));
}
