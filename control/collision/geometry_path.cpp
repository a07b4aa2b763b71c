// The search path of the models' collision geometry files; see geometry_path.hpp.
#include "collision/geometry_path.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace mrqp::collision {

std::vector<std::string> geometrySearchPath() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("MRQP_COLLISION_GEOMETRY_PATH")) {
    std::string list(env);
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) dirs.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
#ifdef MRQP_COLLISION_GEOMETRY_SOURCE_DIR
  dirs.emplace_back(MRQP_COLLISION_GEOMETRY_SOURCE_DIR);
#endif
#ifdef MRQP_COLLISION_GEOMETRY_INSTALL_DIR
  dirs.emplace_back(MRQP_COLLISION_GEOMETRY_INSTALL_DIR);
#endif
  return dirs;
}

std::string findGeometryFile(const std::string& model) {
  if (model.empty()) return "";
  for (const std::string& dir : geometrySearchPath()) {
    const std::string path = dir + "/" + model + ".yaml";
    if (std::ifstream(path)) return path;
  }
  return "";
}

}  // namespace mrqp::collision
