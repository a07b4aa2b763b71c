// Where the collision geometry files of models are found (docs/collision.md, "Geometry files"):
// a model's file is MODEL.yaml in, first, each folder of the environment variable
// MRQP_COLLISION_GEOMETRY_PATH (':'-separated: a user's own files, which take precedence), then
// the built-in files of the source tree (control/collision/geometry), then their installed copy
// (<prefix>/share/mrqp/collision). Set-up only: reads the environment and the file system.
#pragma once

#include <string>
#include <vector>

namespace mrqp::collision {

/// The folders searched, in order (those of MRQP_COLLISION_GEOMETRY_PATH first).
std::vector<std::string> geometrySearchPath();

/// The path of the first MODEL.yaml found along geometrySearchPath(); empty when none.
std::string findGeometryFile(const std::string& model);

}  // namespace mrqp::collision
