// A scratch folder for a test's files: created under the system's temporary directory with a
// random name, removed with everything in it when the object goes out of scope.
#pragma once

#include <filesystem>
#include <random>
#include <string>
#include <system_error>

namespace mrqp::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "mrqp_test_") {
    std::random_device rd;
    for (;;) {
      path_ = std::filesystem::temp_directory_path() / (prefix + std::to_string(rd()));
      if (std::filesystem::create_directories(path_)) break;
    }
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// The path of `name` inside the folder.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace mrqp::testing
