// Paths of the built-in models' files, fixed at build time (MRQP_SIM_MODELS_DIR,
// MRQP_SIM_SHARED_MODELS_DIR from control/sim/CMakeLists.txt).
#include "sim/model_files.hpp"

#include <sys/stat.h>

namespace mrqp::sim {

namespace {
bool isDirectory(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}
}  // namespace

std::string builtinModelUrdf(const std::string& model) {
  if (model == "panda" || model == "jvrc1" || model == "door" || model == "shadow_hand" || model == "pen") {
    return std::string(MRQP_SIM_MODELS_DIR) + "/" + model + ".urdf";
  }
  return {};
}

bool builtinModelFloating(const std::string& model) { return model == "jvrc1" || model == "pen"; }

std::vector<GeomSpec> builtinModelVisuals(const std::string& model) {
  std::vector<GeomSpec> out;
  if (model == "door") {
    GeomSpec panel;  // around the door link's centre of mass, hinge along z at the origin
    panel.link = "door";
    panel.type = GeomSpec::Type::Box;
    panel.size = Eigen::Vector3d(0.04, 0.86, 2.0);
    panel.pose.xyz = Eigen::Vector3d(-0.00724, 0.441, 1.029);
    out.push_back(panel);
    GeomSpec lever;  // where the scenes' grip contacts put it: handle frame, y −0.03…−0.05
    lever.link = "handle";
    lever.type = GeomSpec::Type::Box;
    lever.size = Eigen::Vector3d(0.02, 0.02, 0.12);
    lever.pose.xyz = Eigen::Vector3d(0.0, -0.04, 0.05);
    out.push_back(lever);
  }
  return out;
}

std::vector<std::string> defaultPackagePath() {
  std::vector<std::string> out;
  if (isDirectory(MRQP_SIM_SHARED_MODELS_DIR)) {
    out.emplace_back(MRQP_SIM_SHARED_MODELS_DIR);
  }
  out.emplace_back(MRQP_SIM_MODELS_DIR);
  return out;
}

}  // namespace mrqp::sim
