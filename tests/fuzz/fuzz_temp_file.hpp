// A private temporary file for the harnesses whose reader takes a path (the drive emulator's
// configuration, meshes, whose format is chosen by the file extension): made once per process
// under $TMPDIR (else /tmp), rewritten for every input, removed at exit.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mrqp::fuzz {

class TempFile {
 public:
  TempFile(const char* stem, const char* extension) {
    const char* dir = std::getenv("TMPDIR");
    path_ = std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/mrqp-fuzz-" + stem + "-" +
            std::to_string(static_cast<long>(getpid())) + extension;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

  /// Replaces the file's content; aborts if the file cannot be written (not the reader's fault).
  void write(const uint8_t* data, std::size_t size) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
      std::perror(path_.c_str());
      std::abort();
    }
  }

 private:
  std::string path_;
};

}  // namespace mrqp::fuzz
