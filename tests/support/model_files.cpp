#include "model_files.hpp"

#include <algorithm>
#include <filesystem>

namespace mrqp::testing {

std::string modelUrdf(const std::string& file) {
  const std::string runtime = std::string(MRQP_MODELS_URDF_DIR) + "/" + file;
  if (std::filesystem::exists(runtime)) return runtime;
  return std::string(MRQP_TEST_MODELS_DIR) + "/" + file;
}

std::vector<std::string> modelUrdfNames() {
  std::vector<std::string> names;
  for (const char* dir : {MRQP_MODELS_URDF_DIR, MRQP_TEST_MODELS_DIR})
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.path().extension() == ".urdf") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace mrqp::testing
