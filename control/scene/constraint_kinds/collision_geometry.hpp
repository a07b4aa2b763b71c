// Collision geometry files (docs/collision.md, "Geometry files"): the convex shapes of one model by
// link, and optionally the SRDF whose disable_collisions pairs are left out:
//
//   srdf: panda.srdf                      # optional, relative to this file
//   links:
//     panda_link1:
//       - {capsule: {radius: 0.09, length: 0.283}, xyz: [0, 0, -0.1915], rpy: [0, 0, 0]}
//       - {sphere: 0.05, xyz: [...]}  - {box: [sx, sy, sz]}  - {hull: [[x, y, z], ...]}
//
// Host-side: allocates and throws SceneError "FILE:LINE: FIELD: message".
#pragma once

#include <string>

#include "collision/shape_set.hpp"

namespace mrqp::scene {

collision::ShapeSet readCollisionGeometryFile(const std::string& path);
collision::ShapeSet readCollisionGeometryString(const std::string& text, const std::string& file);

/// The geometry file of a model by name: <model>.yaml along collision::geometrySearchPath()
/// (MRQP_COLLISION_GEOMETRY_PATH, then the built-in files; "" when there is none).
std::string builtinCollisionGeometry(const std::string& model);

}  // namespace mrqp::scene
