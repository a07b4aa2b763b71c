// Reading a scene file (docs/scenes.md) into a SceneSpec. This checks the structure of the file and
// the range of every value; the names of models, frames and joints are resolved later, against the
// models. Host-side: this allocates and throws.
#pragma once

#include <stdexcept>
#include <string>

#include "scene/scene_spec.hpp"

namespace mrqp::scene {

/// A scene that cannot be read. what() is "FILE:LINE: FIELD: message" (LINE is 1-based, FIELD the
/// dotted path of the offending key, e.g. "tasks[2].weight"), "FILE: cannot open: <reason>" when
/// the file cannot be read, or "FILE:LINE: yaml: <message>" for a YAML syntax error.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(const std::string& message) : std::runtime_error(message) {}
};

/// Reads and checks the scene file at `path`; messages name the file as `path`.
SceneSpec loadSceneFile(const std::string& path);

/// The same for a scene held in memory; messages name it `file_name_for_messages`.
SceneSpec loadSceneString(const std::string& text, const std::string& file_name_for_messages);

}  // namespace mrqp::scene
