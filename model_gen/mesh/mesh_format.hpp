// The interface of the mesh format readers (stl_reader.cpp, obj_reader.cpp, collada_reader.cpp)
// behind readMeshVertices (mesh_reader.hpp): a reader adds the positions it finds to a VertexSet
// (distinct positions in order of first appearance) or throws MeshError with the <problem> part
// of MeshReadResult::error. Internal to mrqp_mesh.
#pragma once

#include <Eigen/Core>

#include "mesh_limits.hpp"

#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

namespace mrqp::gen::mesh {

// Internal error carrying the <problem> part of MeshReadResult::error.
struct MeshError {
  std::string problem;
};

[[noreturn]] inline void fail(std::string problem) { throw MeshError{std::move(problem)}; }

/// Distinct vertex positions, in order of first appearance (-0.0 and 0.0 are the same). At most
/// kMaxMeshVertices positions may be added, repeats included (mesh_limits.hpp).
class VertexSet {
 public:
  void add(const Eigen::Vector3d& p) {
    if (++added_ > kMaxMeshVertices) {
      fail("more than " + std::to_string(kMaxMeshVertices) + " vertices (the mesh vertex limit)");
    }
    Key k{};
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] == 0.0 ? 0.0 : p[i];  // -0.0 and 0.0 are the same position
      std::memcpy(&k.bits[static_cast<std::size_t>(i)], &v, sizeof v);
    }
    if (seen_.insert(k).second) points_.push_back(p);
  }
  std::vector<Eigen::Vector3d> take() { return std::move(points_); }
  bool empty() const { return points_.empty(); }

 private:
  struct Key {
    std::uint64_t bits[3];
    bool operator==(const Key& o) const {
      return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      for (const std::uint64_t b : k.bits) {
        h ^= b + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
      }
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_set<Key, KeyHash> seen_;
  std::vector<Eigen::Vector3d> points_;
  std::size_t added_ = 0;
};

/// Binary or ASCII STL (mesh_reader.hpp says how the two are told apart).
void readStl(const std::string& data, VertexSet& out);
/// Wavefront OBJ: the "v x y z [w]" lines.
void readObj(const std::string& data, VertexSet& out);
/// COLLADA 1.4/1.5 through the minimal XML reader (xml_document.hpp).
void readDae(const std::string& data, VertexSet& out);

}  // namespace mrqp::gen::mesh
