#include <catch2/catch.hpp>

#include "convex_hull.hpp"
#include "mesh_reader.hpp"
#include "temp_dir.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;
using mrqp::gen::MeshReadResult;
using mrqp::gen::readMeshVertices;
using mrqp::gen::resolveMeshUri;
using Vec3 = Eigen::Vector3d;

namespace {

const std::string kData = std::string(MRQP_TEST_DATA_DIR) + "/meshes/";

// A fresh directory under the system's temporary directory, removed at the end.
using mrqp::testing::TempDir;

void writeFile(const std::string& path, const std::string& bytes) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out.good());
}

void putU32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}

void putF32(std::string& s, float f) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof f);
  putU32(s, bits);
}

using Triangle = std::array<std::array<float, 3>, 3>;

// Binary STL bytes, little-endian as the format requires, whatever the host.
std::string binaryStl(const std::string& header, const std::vector<Triangle>& tris) {
  std::string s = header.substr(0, 80);
  s.resize(80, ' ');
  putU32(s, static_cast<std::uint32_t>(tris.size()));
  for (const Triangle& t : tris) {
    for (int k = 0; k < 3; ++k) putF32(s, 0.0F);  // normal
    for (const auto& v : t) {
      for (const float c : v) putF32(s, c);
    }
    s += '\0';
    s += '\0';
  }
  return s;
}

// A tetrahedron whose coordinates include 0.1f (not exact in binary).
const std::vector<std::array<float, 3>> kTetra{
    {0.0F, 0.0F, 0.0F}, {0.1F, 0.0F, 0.0F}, {0.0F, 0.25F, 0.0F}, {0.0F, 0.0F, -2.5F}};

std::vector<Triangle> tetraTriangles() {
  const auto& p = kTetra;
  return {Triangle{p[0], p[2], p[1]}, Triangle{p[0], p[1], p[3]}, Triangle{p[0], p[3], p[2]},
          Triangle{p[1], p[2], p[3]}};
}

// The distinct corners in order of first appearance in tetraTriangles().
std::vector<Vec3> tetraVertices() {
  std::vector<Vec3> v;
  for (const std::size_t i : {std::size_t{0}, std::size_t{2}, std::size_t{1}, std::size_t{3}})
    v.emplace_back(kTetra[i][0], kTetra[i][1], kTetra[i][2]);
  return v;
}

std::string asciiTetra(const std::string& eol = "\n") {
  std::string s = "solid tetra" + eol;
  for (const Triangle& t : tetraTriangles()) {
    s += "  facet normal 0 0 0" + eol + "    outer loop" + eol;
    for (const auto& v : t) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "      vertex %.9g %.9g %.9g", double(v[0]), double(v[1]), double(v[2]));
      s += buf + eol;
    }
    s += "    endloop" + eol + "  endfacet" + eol;
  }
  return s + "endsolid tetra" + eol;
}

bool sameSet(std::vector<Vec3> a, std::vector<Vec3> b) {
  auto less = [](const Vec3& x, const Vec3& y) {
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  };
  std::sort(a.begin(), a.end(), less);
  std::sort(b.begin(), b.end(), less);
  return a == b;
}

bool near(const std::vector<Vec3>& got, const std::vector<Vec3>& want, double tol) {
  if (got.size() != want.size()) return false;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if ((got[i] - want[i]).norm() > tol) return false;
  }
  return true;
}

// Sets an environment variable for the scope, restoring it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

// ---- STL ------------------------------------------------------------------------------

TEST_CASE("mesh reader: binary STL is read, including one whose header starts with \"solid\"",
          "[mesh][stl]") {
  TempDir dir;
  const std::string header = GENERATE(std::string("binary STL written by the mrqp tests"),
                                      std::string("solid tetra (a binary file despite its header)"));
  const std::string path = dir.file("tetra.stl");
  writeFile(path, binaryStl(header, tetraTriangles()));
  REQUIRE(fs::file_size(path) == 84 + 50 * 4);

  const MeshReadResult r = readMeshVertices(path);
  INFO(r.error);
  REQUIRE(r.ok);
  REQUIRE(r.error.empty());
  // Twelve facet corners, four distinct positions, exactly the float values.
  REQUIRE(r.vertices == tetraVertices());
}

TEST_CASE("mesh reader: ASCII STL is read", "[mesh][stl]") {
  TempDir dir;
  SECTION("LF line ends") {
    const std::string path = dir.file("tetra.stl");
    writeFile(path, asciiTetra());
    const MeshReadResult r = readMeshVertices(path);
    INFO(r.error);
    REQUIRE(r.ok);
    // The text holds 9 significant digits, read as doubles (0.100000001, not 0.1f).
    REQUIRE(near(r.vertices, tetraVertices(), 1e-8));
  }
  SECTION("CRLF line ends, upper-case keywords and extension, two solids") {
    std::string text = asciiTetra("\r\n");
    for (const char* kw : {"solid", "facet", "normal", "outer", "loop", "vertex", "endloop", "endfacet"}) {
      std::string up = kw;
      std::transform(up.begin(), up.end(), up.begin(), [](char c) { return char(std::toupper(c)); });
      for (std::size_t at = text.find(kw); at != std::string::npos; at = text.find(kw, at + 1)) {
        text.replace(at, up.size(), up);
      }
    }
    text +=
        "solid second\n facet normal 0 0 1\n outer loop\n vertex 5 5 5\n vertex 6 5 5\n"
        " vertex 5 6 5\n endloop\n endfacet\nendsolid second\n";
    const std::string path = dir.file("TETRA.STL");
    writeFile(path, text);
    const MeshReadResult r = readMeshVertices(path);
    INFO(r.error);
    REQUIRE(r.ok);
    std::vector<Vec3> want = tetraVertices();
    want.insert(want.end(), {Vec3(5, 5, 5), Vec3(6, 5, 5), Vec3(5, 6, 5)});
    REQUIRE(near(r.vertices, want, 1e-8));
  }
}

TEST_CASE("mesh reader: malformed and truncated STL files give clear errors", "[mesh][stl]") {
  TempDir dir;
  const std::string path = dir.file("bad.stl");
  const std::string binary = binaryStl("binary", tetraTriangles());
  const std::string solidBinary = binaryStl("solid but binary", tetraTriangles());

  SECTION("binary cut in the middle of a triangle") {
    writeFile(path, binary.substr(0, binary.size() - 30));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE(r.vertices.empty());
    REQUIRE_THAT(r.error, StartsWith("mesh '" + path + "': truncated binary STL"));
    REQUIRE_THAT(r.error,
                 Contains("declares 4 triangles, i.e. 84 + 50*4 = 284 bytes, but the file has 254 bytes"));
  }
  SECTION("binary with a \"solid\" header, cut") {
    writeFile(path, solidBinary.substr(0, 200));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, StartsWith("mesh '" + path + "': truncated binary STL"));
    REQUIRE_THAT(r.error, Contains("starts with \"solid\""));
  }
  SECTION("binary with trailing bytes") {
    writeFile(path, binary + "extra");
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("binary STL size mismatch"));
  }
  SECTION("shorter than the binary header") {
    writeFile(path, binary.substr(0, 50));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE(r.error ==
            "mesh '" + path + "': truncated binary STL: 50 bytes, shorter than the 84-byte header");
  }
  SECTION("empty file") {
    writeFile(path, "");
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("truncated binary STL: 0 bytes"));
  }
  SECTION("binary with no triangles") {
    writeFile(path, binaryStl("nothing", {}));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE(r.error == "mesh '" + path + "': no vertices");
  }
  SECTION("ASCII without endsolid") {
    const std::string text = asciiTetra();
    writeFile(path, text.substr(0, text.rfind("endsolid")));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE(r.error == "mesh '" + path + "': truncated ASCII STL: missing 'endsolid' at the end of the file");
  }
  SECTION("ASCII cut inside a vertex") {
    const std::string text = asciiTetra();
    writeFile(path, text.substr(0, text.find("vertex", text.find("vertex") + 1) + 9));
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("truncated ASCII STL: incomplete vertex at line 5"));
  }
  SECTION("ASCII with a bad number") {
    writeFile(path, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\n");
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("malformed ASCII STL: bad vertex coordinate 'zero' at line 5"));
  }
  SECTION("ASCII facet with two vertices") {
    writeFile(path,
              "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
              "endfacet\nendsolid x\n");
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("malformed ASCII STL: facet loop with 2 vertices (expected 3) at line 6"));
  }
  SECTION("ASCII solid without facets") {
    writeFile(path, "solid empty\nendsolid empty\n");
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, Contains("no vertices"));
  }
}

// ---- OBJ ------------------------------------------------------------------------------

TEST_CASE("mesh reader: OBJ vertices are read", "[mesh][obj]") {
  const std::string path = kData + "cube.obj";
  const MeshReadResult r = readMeshVertices(path);
  INFO(r.error);
  REQUIRE(r.ok);
  REQUIRE(r.vertices.size() == 8);  // nine v lines, one repeated
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  REQUIRE(sameSet(r.vertices, corners));
  REQUIRE(r.vertices[7] == Vec3(0, 1, 1));  // the tab-indented line with '+' and colours

  // ...and its hull is the unit cube.
  const mrqp::gen::ConvexHull h = mrqp::gen::convexHull(r.vertices);
  REQUIRE(h.vertices.size() == 8);
  REQUIRE(h.faces.size() == 12);
}

TEST_CASE("mesh reader: malformed OBJ files give clear errors", "[mesh][obj]") {
  const std::string path = kData + "bad_vertex.obj";
  const MeshReadResult r = readMeshVertices(path);
  REQUIRE_FALSE(r.ok);
  REQUIRE(r.error == "mesh '" + path + "': malformed OBJ: bad vertex coordinate 'x1' at line 4");

  TempDir dir;
  const std::string few = dir.file("few.obj");
  writeFile(few, "v 1 2\n");
  REQUIRE_THAT(readMeshVertices(few).error,
               Contains("malformed OBJ: vertex with fewer than 3 coordinates at line 1"));
  const std::string none = dir.file("none.obj");
  writeFile(none, "# only faces\nf 1 2 3\nvn 0 0 1\n");
  REQUIRE(readMeshVertices(none).error == "mesh '" + none + "': no vertices");
}

// ---- COLLADA --------------------------------------------------------------------------

TEST_CASE("mesh reader: COLLADA positions are read with units and node transforms", "[mesh][dae]") {
  const MeshReadResult r = readMeshVertices(kData + "tetra_scene.dae");
  INFO(r.error);
  REQUIRE(r.ok);
  // Millimetres to metres; the tetrahedron rotated +90 deg about z by <matrix> then raised by
  // 500 mm; the marker scaled by 2 then rotated +90 deg about z by <rotate>, through
  // <instance_node>; the unused geometry left out.
  const std::vector<Vec3> want{{0, 0, 0.5},  {0, 1, 0.5},   {-1, 0, 0.5}, {0, 0, 1.5},
                               {0, 0.02, 0}, {-0.02, 0, 0}, {0, 0, 0.02}};
  REQUIRE(near(r.vertices, want, 1e-12));
}

TEST_CASE("mesh reader: COLLADA without a visual scene gives every mesh untransformed", "[mesh][dae]") {
  const MeshReadResult r = readMeshVertices(kData + "no_scene.dae");
  INFO(r.error);
  REQUIRE(r.ok);
  const std::vector<Vec3> want{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 2, 2}, {3, 3, 3}};
  REQUIRE(r.vertices == want);
}

TEST_CASE("mesh reader: malformed COLLADA files give clear errors", "[mesh][dae]") {
  SECTION("truncated XML") {
    const std::string path = kData + "truncated.dae";
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE_THAT(r.error, StartsWith("mesh '" + path + "': malformed XML: "));
    REQUIRE_THAT(r.error, EndsWith("at line 16"));  // the file ends inside a <param> tag on line 16
  }
  SECTION("float_array shorter than declared") {
    const std::string path = kData + "bad_count.dae";
    const MeshReadResult r = readMeshVertices(path);
    REQUIRE_FALSE(r.ok);
    REQUIRE(r.error ==
            "mesh '" + path +
                "': malformed COLLADA: <float_array id='short-pos-array'> declares 12 values but holds 8");
  }
  TempDir dir;
  const std::string path = dir.file("x.dae");
  SECTION("not COLLADA") {
    writeFile(path, "<?xml version=\"1.0\"?>\n<robot name=\"r\"/>\n");
    REQUIRE_THAT(readMeshVertices(path).error, Contains("malformed COLLADA: the root element is <robot>"));
  }
  SECTION("mismatched tags") {
    writeFile(path, "<COLLADA>\n<asset>\n</COLLADA>\n");
    REQUIRE_THAT(readMeshVertices(path).error,
                 Contains("malformed XML: closing tag </COLLADA> does not match <asset> at line 3"));
  }
  SECTION("reference to a missing source") {
    writeFile(path,
              "<COLLADA><library_geometries><geometry id='g'><mesh><vertices id='v'>"
              "<input semantic='POSITION' source='#nowhere'/></vertices></mesh></geometry>"
              "</library_geometries></COLLADA>");
    REQUIRE_THAT(readMeshVertices(path).error, Contains("malformed COLLADA") && Contains("'#nowhere'"));
  }
  SECTION("bad number") {
    writeFile(path,
              "<COLLADA><library_geometries><geometry id='g'><mesh><source id='s'>"
              "<float_array id='a'>0 0 0 1 zero 0</float_array></source><vertices id='v'>"
              "<input semantic='POSITION' source='#s'/></vertices></mesh></geometry>"
              "</library_geometries></COLLADA>");
    REQUIRE_THAT(readMeshVertices(path).error,
                 Contains("malformed COLLADA: bad number 'zero' in <float_array id='a'>"));
  }
  SECTION("no geometry") {
    writeFile(path, "<COLLADA version='1.4.1'><asset><unit meter='1'/></asset></COLLADA>");
    REQUIRE(readMeshVertices(path).error == "mesh '" + path + "': no vertices");
  }
}

// ---- general errors -------------------------------------------------------------------

TEST_CASE("mesh reader: missing files, directories and unsupported formats", "[mesh]") {
  const std::string missing = "/nonexistent/mrqp/mesh.stl";
  const MeshReadResult r = readMeshVertices(missing);
  REQUIRE_FALSE(r.ok);
  REQUIRE(r.vertices.empty());
  REQUIRE(r.error == "mesh '/nonexistent/mrqp/mesh.stl': file not found");
  REQUIRE(readMeshVertices("").error == "mesh '': file not found");

  TempDir dir;
  const std::string ply = dir.file("mesh.ply");
  writeFile(ply, "ply\nformat ascii 1.0\nend_header\n");
  REQUIRE(readMeshVertices(ply).error ==
          "mesh '" + ply + "': unsupported mesh format '.ply' (supported: .stl, .obj, .dae)");
  const std::string noExt = dir.file("mesh");
  writeFile(noExt, "v 0 0 0\n");
  REQUIRE_THAT(readMeshVertices(noExt).error, Contains("unsupported mesh format (no file extension"));
  const std::string folder = dir.file("folder.stl");
  fs::create_directories(folder);
  REQUIRE(readMeshVertices(folder).error == "mesh '" + folder + "': not a regular file");
}

// ---- URIs -----------------------------------------------------------------------------

TEST_CASE("mesh reader: package:// and file:// URIs are resolved", "[mesh][uri]") {
  TempDir dir;
  const fs::path src = dir.path() / "ws" / "src";
  const std::string mesh = (src / "my_pkg" / "meshes" / "link.STL").string();
  writeFile(mesh, "solid\nendsolid\n");
  const std::string uri = "package://my_pkg/meshes/link.STL";

  SECTION("under a package path") {
    REQUIRE(resolveMeshUri(uri, "", {"/nonexistent", src.string()}) == mesh);
    REQUIRE(resolveMeshUri(uri, "", {src.string() + "/"}) == mesh);
    REQUIRE(resolveMeshUri(uri, "", {(src / "my_pkg").string()}) == mesh);  // the package itself
    REQUIRE(resolveMeshUri("package://my_pkg/meshes/other.stl", "", {src.string()}).empty());
    REQUIRE(resolveMeshUri("package://other_pkg/meshes/link.STL", "", {src.string()}).empty());
    REQUIRE(resolveMeshUri("package://my_pkg", "", {src.string()}).empty());
    REQUIRE(resolveMeshUri("package://my_pkg/meshes", "", {src.string()}).empty());  // a directory
  }
  SECTION("under ROS_PACKAGE_PATH") {
    const ScopedEnv env("ROS_PACKAGE_PATH", "/nonexistent::" + src.string());
    REQUIRE(resolveMeshUri(uri, "", {}) == mesh);
    REQUIRE(resolveMeshUri(uri, "", {"/nonexistent"}) == mesh);
  }
  SECTION("under AMENT_PREFIX_PATH/share") {
    const std::string installed =
        (dir.path() / "install" / "share" / "my_pkg" / "meshes" / "link.STL").string();
    writeFile(installed, "solid\nendsolid\n");
    const ScopedEnv ros("ROS_PACKAGE_PATH", "");
    const ScopedEnv ament("AMENT_PREFIX_PATH", (dir.path() / "install").string());
    REQUIRE(resolveMeshUri(uri, "", {}) == installed);
    REQUIRE(resolveMeshUri(uri, "", {src.string()}) == mesh);  // explicit paths first
  }
  SECTION("file:// URIs") {
    REQUIRE(resolveMeshUri("file://" + mesh, "", {}) == mesh);
    REQUIRE(resolveMeshUri("file://localhost" + mesh, "", {}) == mesh);
    const std::string spaced = (dir.path() / "my mesh.dae").string();
    writeFile(spaced, "<COLLADA/>");
    std::string encoded = "file://" + spaced;
    encoded.replace(encoded.find(' '), 1, "%20");
    REQUIRE(resolveMeshUri(encoded, "", {}) == spaced);
    REQUIRE(resolveMeshUri("file:///nonexistent/mesh.stl", "", {}).empty());
  }
  SECTION("plain paths, relative to the URDF's directory") {
    const std::string urdfDir = (src / "my_pkg" / "urdf").string();
    REQUIRE(resolveMeshUri("../meshes/link.STL", urdfDir, {}) == mesh);
    REQUIRE(resolveMeshUri("file://../meshes/./link.STL", urdfDir, {}) == mesh);
    REQUIRE(resolveMeshUri(mesh, "/somewhere/else", {}) == mesh);
    REQUIRE(resolveMeshUri("link.STL", urdfDir, {}).empty());
  }
  SECTION("other schemes and empty strings") {
    REQUIRE(resolveMeshUri("http://example.com/link.STL", "", {src.string()}).empty());
    REQUIRE(resolveMeshUri("model://my_pkg/meshes/link.STL", "", {src.string()}).empty());
    REQUIRE(resolveMeshUri("", src.string(), {src.string()}).empty());
  }
  SECTION("the resolved file can be read") {
    const std::string resolved = resolveMeshUri(uri, "", {src.string()});
    const MeshReadResult r = readMeshVertices(resolved);
    REQUIRE_FALSE(r.ok);  // an ASCII solid without facets
    REQUIRE(r.error == "mesh '" + mesh + "': no vertices");
  }
}
