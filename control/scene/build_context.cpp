// Name resolution and errors while a scene is built; see build_context.hpp.
#include "scene/build_context.hpp"

#include <sstream>
#include <vector>

#include "scene/scene_yaml.hpp"

namespace mrqp::scene {

namespace {

std::string listOf(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 60; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 60) s += ", …";
  return s;
}

}  // namespace

void BuildContext::fail(const Source& src, const std::string& field, const std::string& msg) {
  std::ostringstream os;
  os << (src.file.empty() ? "<scene>" : src.file) << ":" << src.line << ": " << field << ": " << msg;
  throw SceneError(os.str());
}

int BuildContext::entity(const std::string& name, const Source& src, const std::string& field) const {
  const int i = p_.entityIndex(name);
  if (i < 0) {
    std::vector<std::string> names;
    for (int k = 0; k < p_.entityCount(); ++k) names.push_back(p_.entity(k).name());
    fail(src, field, "unknown entity '" + name + "' (entities: " + listOf(names) + ")");
  }
  return i;
}

int BuildContext::frame(int e, const std::string& name, const Source& src, const std::string& field) const {
  const problem::Entity& en = p_.entity(e);
  const int f = en.frameIndex(name);
  if (f < 0) {
    std::vector<std::string> names;
    for (int k = 0; k < en.frameCount(); ++k) names.emplace_back(en.frameName(k));
    fail(src, field,
         "entity '" + en.name() + "' has no frame '" + name + "' (frames: " + listOf(names) + ")");
  }
  return f;
}

int BuildContext::joint(int e, const std::string& name, const Source& src, const std::string& field) const {
  const problem::Entity& en = p_.entity(e);
  const int k = en.jointIndex(name);
  if (k < 0) {
    std::vector<std::string> names;
    for (int j = 0; j < en.nv() - en.jointOffset(); ++j) names.emplace_back(en.jointName(j));
    fail(src, field,
         "entity '" + en.name() + "' has no joint '" + name + "' (joints: " + listOf(names) + ")");
  }
  return k;
}

int BuildContext::contact(const std::string& name, const Source& src, const std::string& field) const {
  auto it = contacts_.find(name);
  if (it == contacts_.end()) fail(src, field, "unknown contact '" + name + "'");
  return it->second;
}

}  // namespace mrqp::scene
