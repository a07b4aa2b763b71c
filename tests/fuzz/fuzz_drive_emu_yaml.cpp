// libFuzzer harness: the drive emulator's configuration (tools/drive_emu, loadConfig), which
// reads a file: each input is written to a private temporary file first.
//
// Properties beyond "no crash, no undefined behaviour, no allocation beyond libFuzzer's limit":
// loadConfig never throws (it reports by return value), a rejection carries a message, and an
// accepted configuration passes validateConfig.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "drive_emu.hpp"
#include "fuzz_check.hpp"
#include "fuzz_temp_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mrqp::fuzz::TempFile file("drive_emu", ".yaml");
  file.write(data, size);
  mrqp::drive_emu::EmuConfig config;
  std::string error;
  if (!mrqp::drive_emu::loadConfig(file.path(), &config, &error)) {
    MRQP_FUZZ_CHECK(!error.empty());
    return 0;
  }
  std::string again;
  MRQP_FUZZ_CHECK(mrqp::drive_emu::validateConfig(config, file.path(), &again));
  return 0;
}
