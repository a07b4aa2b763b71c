// Hostile mesh files against the limits of the mesh readers (model_gen/mesh/mesh_limits.hpp): each
// input recreated here, each refused with an error naming the file and the limit, none read whole
// or walked without bound; and the COLLADA <rotate> axis normalised without overflow.
#include <catch2/catch.hpp>

#include "mesh_format.hpp"
#include "mesh_limits.hpp"
#include "mesh_reader.hpp"
#include "temp_dir.hpp"
#include "xml_document.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using mrqp::gen::MeshReadResult;
using mrqp::gen::readMeshVertices;

namespace {

using mrqp::testing::TempDir;

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream out(path, std::ios::binary);
  out << text;
  REQUIRE(out.good());
  return path;
}

const char* kTriangleGeometry =
    "<library_geometries><geometry id='g'><mesh>"
    "<source id='p'><float_array id='pa' count='9'>0 0 0 1 0 0 0 1 0</float_array>"
    "<technique_common><accessor source='#pa' count='3' stride='3'/></technique_common></source>"
    "<vertices id='v'><input semantic='POSITION' "
    "source='#p'/></vertices></mesh></geometry></library_geometries>";

/// The 3.9 KB file of the finding: node k (k < levels) instantiates node k+1 twice; the last node
/// holds the geometry. Walking it whole is 2^levels visits.
std::string instanceNodeBomb(int levels) {
  std::string s = "<?xml version='1.0'?><COLLADA>";
  s += kTriangleGeometry;
  s += "<library_nodes>";
  for (int k = 0; k < levels; ++k) {
    const std::string next = "#n" + std::to_string(k + 1);
    s += "<node id='n" + std::to_string(k) + "'><instance_node url='" + next + "'/><instance_node url='" +
         next + "'/></node>";
  }
  s += "<node id='n" + std::to_string(levels) + "'><instance_geometry url='#g'/></node></library_nodes>";
  s += "<library_visual_scenes><visual_scene id='s'><node><instance_node url='#n0'/></node></visual_scene>"
       "</library_visual_scenes><scene><instance_visual_scene url='#s'/></scene></COLLADA>";
  return s;
}

}  // namespace

TEST_CASE("hostile meshes: COLLADA <instance_node> references doubling over 40 levels hit the visit limit",
          "[mesh][hostile]") {
  TempDir dir;
  const std::string bomb = instanceNodeBomb(40);
  CHECK(bomb.size() < 4500);
  const std::string path = write(dir, "bomb.dae", bomb);
  const auto t0 = std::chrono::steady_clock::now();
  const MeshReadResult r = readMeshVertices(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error, StartsWith("mesh '" + path + "': ") &&
                          Contains("more than 100000 node visits (the COLLADA node-visit limit") &&
                          Contains("<node id='n"));
  WARN("the 2^40-visit file was refused after " << seconds << " s");

  // the same structure with 10 levels (1024 visits of the geometry) is read: one triangle
  const MeshReadResult small = readMeshVertices(write(dir, "small.dae", instanceNodeBomb(10)));
  REQUIRE(small.ok);
  CHECK(small.vertices.size() == 3);
}

TEST_CASE("hostile meshes: a mesh instanced more often than the vertex limit allows", "[mesh][hostile]") {
  // 60 vertices, 1,000 instances per node, that node instanced 100 times: 6,000,000 vertices > 5,000,000
  std::string floats;
  for (int i = 0; i < 60; ++i) floats += std::to_string(i) + " 0 0 ";
  std::string s =
      "<COLLADA><library_geometries><geometry id='g'><mesh><source id='p'><float_array id='pa' "
      "count='180'>" +
      floats +
      "</float_array></source><vertices id='v'><input semantic='POSITION' source='#p'/></vertices>"
      "</mesh></geometry></library_geometries><library_nodes><node id='many'>";
  for (int i = 0; i < 1000; ++i) s += "<instance_geometry url='#g'/>";
  s += "</node></library_nodes><library_visual_scenes><visual_scene id='s'><node>";
  for (int i = 0; i < 100; ++i) s += "<instance_node url='#many'/>";
  s += "</node></visual_scene></library_visual_scenes></COLLADA>";
  TempDir dir;
  const MeshReadResult r = readMeshVertices(write(dir, "many.dae", s));
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error, Contains("more than 5000000 vertices (the mesh vertex limit)"));
}

TEST_CASE("hostile meshes: 100,000 nested XML elements in a COLLADA file", "[mesh][hostile]") {
  std::string s = "<COLLADA>";
  for (int i = 0; i < 100000; ++i) s += "<node>";
  for (int i = 0; i < 100000; ++i) s += "</node>";
  s += "</COLLADA>";
  TempDir dir;
  const MeshReadResult r = readMeshVertices(write(dir, "deep.dae", s));
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error, Contains("<node> nested deeper than 256 levels at line 1"));
}

TEST_CASE("hostile meshes: files over the size limit and devices are refused without reading them",
          "[mesh][hostile]") {
  TempDir dir;
  const std::string big = write(dir, "huge.stl", "solid x\nendsolid x\n");
  fs::resize_file(big, std::uintmax_t{1} << 40);  // 1 TiB, sparse
  const MeshReadResult r = readMeshVertices(big);
  CHECK_FALSE(r.ok);
  CHECK(r.error == "mesh '" + big + "': larger than the 67108864-byte mesh limit (1099511627776 bytes)");
  fs::resize_file(big, mrqp::gen::kMaxMeshBytes + 1);
  CHECK_THAT(readMeshVertices(big).error,
             Contains("larger than the 67108864-byte mesh limit (67108865 bytes)"));

  CHECK(readMeshVertices("/dev/zero").error == "mesh '/dev/zero': not a regular file");
  const std::string zero = dir.file("zero.stl");
  fs::create_symlink("/dev/zero", zero);
  CHECK(readMeshVertices(zero).error == "mesh '" + zero + "': not a regular file");
}

TEST_CASE("hostile meshes: a COLLADA <rotate> about a huge axis is a rotation", "[mesh][hostile]") {
  const std::string s =
      std::string("<COLLADA>") + kTriangleGeometry +
      "<library_visual_scenes><visual_scene id='s'><node><rotate>1e300 0 0 90</rotate>"
      "<instance_geometry url='#g'/></node></visual_scene></library_visual_scenes></COLLADA>";
  TempDir dir;
  const MeshReadResult r = readMeshVertices(write(dir, "rot.dae", s));
  REQUIRE(r.ok);
  REQUIRE(r.vertices.size() == 3);
  // (0, 1, 0) turned 90 degrees about x is (0, 0, 1)
  CHECK((r.vertices[2] - Eigen::Vector3d(0, 0, 1)).norm() < 1e-15);
  CHECK((r.vertices[1] - Eigen::Vector3d(1, 0, 0)).norm() < 1e-15);
}

TEST_CASE("hostile meshes: ids and references with control characters give one error line",
          "[mesh][hostile]") {
  const std::string s =
      "<COLLADA><library_visual_scenes><visual_scene id='s&#10;x'><node id='n&#13;&#10;static int i;'>"
      "<instance_geometry name='g&#9;&#10;x' "
      "url='#missing&#10;id'/></node></visual_scene></library_visual_scenes></COLLADA>";
  TempDir dir;
  const MeshReadResult r = readMeshVertices(write(dir, "ids.dae", s));
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error, Contains("<instance_geometry name='g??x'> refers to missing '#missing?id'"));
  CHECK(r.error.find('\n') == std::string::npos);
  CHECK(r.error.find('\r') == std::string::npos);
}

TEST_CASE("hostile meshes: a node with many children, visited often, hits the scene-element limit",
          "[mesh][hostile]") {
  // 25,000 children examined on each of 100 visits: 2,500,000 > 2,000,000, in a 200 KB file
  std::string s = std::string("<COLLADA>") + kTriangleGeometry + "<library_nodes><node id='wide'>";
  for (int i = 0; i < 25000; ++i) s += "<extra/>";
  s += "<instance_geometry url='#g'/></node></library_nodes><library_visual_scenes><visual_scene "
       "id='s'><node>";
  for (int i = 0; i < 100; ++i) s += "<instance_node url='#wide'/>";
  s += "</node></visual_scene></library_visual_scenes></COLLADA>";
  TempDir dir;
  const MeshReadResult r = readMeshVertices(write(dir, "wide.dae", s));
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error,
             Contains("more than 2000000 elements examined in the visual scene (the COLLADA scene limit) at "
                      "<node id='wide'>"));
}

TEST_CASE("hostile meshes: the XML reader's node and depth limits, counted exactly", "[mesh][hostile]") {
  using mrqp::gen::mesh::MeshError;
  using mrqp::gen::mesh::XmlDocument;
  using mrqp::gen::mesh::XmlLimits;
  auto error = [](const std::string& xml, XmlLimits limits) {
    try {
      const XmlDocument doc(xml, limits);
    } catch (const MeshError& e) {
      return e.problem;
    }
    return std::string("(accepted)");
  };
  // 4 elements and 6 attributes: 10 nodes
  const std::string ten = "<a x='1' y='2'>\n<b z='3'/>\n<c u='4' v='5' w='6'><d/></c></a>";
  CHECK(error(ten, XmlLimits{3, 10}) == "(accepted)");
  CHECK(error(ten, XmlLimits{3, 9}) == "more than 9 XML elements and attributes at line 3");
  CHECK(error(ten, XmlLimits{2, 10}) == "<d> nested deeper than 2 levels at line 3");
}
