// Where the files of the built-in models are: the URDF a model name of the scene files was
// generated from, and the folders that package:// mesh URIs are resolved against. The one place
// that knows these paths.
#pragma once

#include <string>
#include <vector>

#include "sim/plant_spec.hpp"

namespace mrqp::sim {

/// The URDF of a built-in model ("panda", "jvrc1", "door"); empty when `model` is not one.
std::string builtinModelUrdf(const std::string& model);

/// Whether the built-in model has a floating base (its generated model's, FLOATING_BASE in
/// control/scene/CMakeLists.txt): jvrc1.
bool builtinModelFloating(const std::string& model);

/// Shapes drawn (never collided) for a built-in model whose URDF has no geometry: the door's panel
/// and handle lever, so that renders show it. Empty for the others.
std::vector<GeomSpec> builtinModelVisuals(const std::string& model);

/// The default package search path: the shared model folder beside the source tree when it
/// exists (its meshes, convex hulls), then the folder of the built-in URDFs.
std::vector<std::string> defaultPackagePath();

}  // namespace mrqp::sim
