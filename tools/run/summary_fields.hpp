// Members added to a written summary.json by a scene's own measurements (docs/loop.md,
// "summary.json"; e.g. the carrying scenes' fields, carry_watch.hpp), without the summary writer
// knowing them: the file's closing brace is replaced by the new members and a new brace.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mrqp::run {

/// Appends `fields` (name, JSON text of the value) to the object of the JSON file at `path`.
/// False when the file cannot be read or written or does not end with an object's '}'.
bool appendSummaryFields(const std::string& path,
                         const std::vector<std::pair<std::string, std::string>>& fields);

}  // namespace mrqp::run
