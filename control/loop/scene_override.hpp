// `--set KEY=VALUE` (docs/loop.md): one value of a scene file replaced by its YAML path before
// the scene is read, e.g. `settings.duration=2`, `tasks[0].weight=50`,
// `tasks[door_angle].target=[-0.4]` (a list item by index or by its `name`),
// `entities[box].mass=3`. The value is YAML. A value written in the file on one line is replaced
// in place, so every later error still names the file's own lines; a key the file does not have
// is added and the scene re-emitted. A path that does not exist throws SceneError
// "FILE:LINE: PATH: message". Host-side.
#pragma once

#include <string>

namespace mrqp::loop {

/// `text` (the scene file `file`) with `assignment` ("KEY=VALUE") applied.
std::string applySceneOverride(const std::string& text, const std::string& file,
                               const std::string& assignment);

}  // namespace mrqp::loop
