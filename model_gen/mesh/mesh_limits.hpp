// The limits of the mesh readers (readMeshVertices, mesh_reader.hpp): file size, XML size of a
// COLLADA file, the work of walking a COLLADA scene and the vertices read. Each is a choice
// (docs/robustness.md, "Model generator"); exceeding one is a MeshReadResult error naming the
// file, the element and the limit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace mrqp::gen {

/// Largest mesh file read, in bytes (checked before reading; a longer stream is cut there).
inline constexpr std::uint64_t kMaxMeshBytes = 64u * 1024u * 1024u;
/// Vertex positions read from one mesh file, repeats included (a COLLADA mesh instanced by
/// several nodes counts once per instance; an STL triangle counts 3).
inline constexpr std::size_t kMaxMeshVertices = 5000000;
/// Elements and attributes of a COLLADA file together.
inline constexpr std::size_t kMaxXmlNodes = 2000000;
/// Deepest element nesting of a COLLADA file.
inline constexpr int kMaxXmlDepth = 256;
/// Nodes visited while walking a COLLADA visual scene, every visit through <instance_node>
/// counted (two references per node over 40 levels would be 2^40 visits).
inline constexpr std::size_t kMaxColladaNodeVisits = 100000;
/// Child elements examined over all those visits (a node with many children, visited often).
inline constexpr std::size_t kMaxColladaSceneElements = 2000000;

}  // namespace mrqp::gen
