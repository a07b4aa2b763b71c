// Members added to a written summary.json by a scene's own measurements (docs/loop.md,
// "summary.json"; e.g. the carrying scenes' fields, carry_watch.hpp), without the summary writer
// knowing them: the file's closing brace is replaced by the new members and a new brace.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mrqp::run {

/// A number as JSON text ("%.9g"; null when not finite).
std::string jsonNumber(double v);
/// A string as a JSON string literal (quotes, backslashes and control characters escaped).
std::string jsonString(const std::string& s);

/// Appends `fields` (name, JSON text of the value) to the object of the JSON file at `path`.
/// False when the file cannot be read or written or does not end with an object's '}'.
bool appendSummaryFields(const std::string& path,
                         const std::vector<std::pair<std::string, std::string>>& fields);

}  // namespace mrqp::run
