// The limits mrqp-gen puts on a URDF before and while it builds a model from it: file size, XML
// nesting, numbers of elements, name length and the range of every number read. Each one is a
// choice (docs/robustness.md, "Model generator"), checked with an error naming the file, the
// element and the limit; none depends on the size of a stack. The mesh files' limits are in
// model_gen/mesh/mesh_limits.hpp.
#pragma once

#include <cstddef>
#include <cstdint>

namespace mrqp::gen {

/// Largest URDF file read, in bytes (checked before reading; a longer stream is cut there).
inline constexpr std::uint64_t kMaxUrdfBytes = 32u * 1024u * 1024u;
/// Deepest element nesting of a URDF (<robot> is level 1), checked before urdfdom parses it.
inline constexpr int kMaxUrdfDepth = 64;
/// Elements and attributes of a URDF together, checked before urdfdom parses it.
inline constexpr std::size_t kMaxUrdfNodes = 2000000;
/// <link> and <joint> elements of one <robot>, checked before urdfdom parses it.
inline constexpr std::size_t kMaxLinks = 10000;
inline constexpr std::size_t kMaxJoints = 10000;
/// Collision elements of the whole robot (each becomes a table entry of the generated code).
inline constexpr std::size_t kMaxCollisions = 10000;
/// Longest chain of mimic joints following one another (a mimics b, which mimics c, ...).
inline constexpr std::size_t kMaxMimicChain = 64;
/// Longest robot, link or joint name, in bytes (name_rule.hpp states the whole rule).
inline constexpr std::size_t kMaxNameLength = 256;

/// Ranges of the numbers read from a URDF (absolute values, SI units). A number outside its
/// range is an error naming the element and field, as a NaN or an infinity is.
inline constexpr double kMaxLength = 1e4;           ///< m: origins, collision sizes, mesh vertices
inline constexpr double kMaxMass = 1e6;             ///< kg
inline constexpr double kMaxInertia = 1e8;          ///< kg·m², each of ixx ... izz
inline constexpr double kMaxJointLimit = 1e9;       ///< lower, upper, velocity, effort of <limit>
inline constexpr double kMaxMimicFactor = 1e6;      ///< multiplier and offset of <mimic>
inline constexpr double kMaxMeshScale = 1e6;        ///< each component of <mesh scale>
inline constexpr double kMinAxisComponent = 1e-12;  ///< an axis whose largest |component| is below is zero

}  // namespace mrqp::gen
