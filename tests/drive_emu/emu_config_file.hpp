// The YAML configuration file of mrqp-drive-emu's emulator for the tests: the text written to a
// file in the working folder, as loadConfig() reads it (tools/drive_emu, docs/drivers.md).
#pragma once

#include <fstream>
#include <string>

namespace drive_emu_test {

// Writes `text` into `file`, replacing what was there.
inline void writeConfigFile(const std::string& file, const std::string& text) {
  std::ofstream f(file);
  f << text;
}

}  // namespace drive_emu_test
