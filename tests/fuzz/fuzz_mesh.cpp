// libFuzzer harness: the mesh readers of the model generator (model_gen/mesh: binary and ASCII STL,
// Wavefront OBJ, COLLADA) through their public entry readMeshVertices, which chooses the format by
// the file extension: every input is read as each of the three formats.
//
// Properties beyond "no crash, no undefined behaviour, no allocation beyond libFuzzer's limit, no
// hang": a read either succeeds with at least one vertex, every coordinate finite, no position
// twice, or fails with one error line naming the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>

#include "fuzz_check.hpp"
#include "fuzz_temp_file.hpp"
#include "mesh_reader.hpp"

namespace {

void readAs(const mrqp::fuzz::TempFile& file, const uint8_t* data, size_t size) {
  file.write(data, size);
  const mrqp::gen::MeshReadResult r = mrqp::gen::readMeshVertices(file.path());
  if (!r.ok) {
    MRQP_FUZZ_CHECK(r.vertices.empty());
    MRQP_FUZZ_CHECK(r.error.rfind("mesh '" + file.path() + "': ", 0) == 0);
    if (r.error.find('\n') != std::string::npos) std::fprintf(stderr, "error text: [%s]\n", r.error.c_str());
    MRQP_FUZZ_CHECK(r.error.find('\n') == std::string::npos);
    return;
  }
  MRQP_FUZZ_CHECK(!r.vertices.empty());
  std::set<std::tuple<double, double, double>> seen;
  for (const Eigen::Vector3d& v : r.vertices) {
    MRQP_FUZZ_CHECK(std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()));
    MRQP_FUZZ_CHECK(seen.emplace(v.x() + 0.0, v.y() + 0.0, v.z() + 0.0).second);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mrqp::fuzz::TempFile stl("mesh", ".stl");
  static const mrqp::fuzz::TempFile obj("mesh", ".obj");
  static const mrqp::fuzz::TempFile dae("mesh", ".dae");
  readAs(stl, data, size);
  readAs(obj, data, size);
  readAs(dae, data, size);
  return 0;
}
