// Reading `candump -L` log lines: "(seconds.micro) iface ID#DATA", "ID##<flags>DATA" for CAN FD,
// "ID#R" for remote frames; 8-hex-digit IDs are extended (error frames carry CAN_ERR_FLAG).
#pragma once

#include <string>

#include "mrqp/firmware_if/frame.h"

namespace mrqp::tools {

struct LogFrame {
  double time = 0.0;  ///< seconds, as logged
  std::string iface;
  mrqp_fw_frame frame{};     ///< 11-bit id, data, MRQP_FW_FRAME_* flags
  bool extended = false;     ///< 29-bit identifier (not part of mrqp's contract)
  bool error_frame = false;  ///< a SocketCAN error frame (CAN_ERR_FLAG in the identifier)
  bool remote = false;
  unsigned raw_id = 0;  ///< identifier as logged (with flag bits for error frames)
};

/// Parses one line. Returns false with `error` set (naming what is wrong) on a malformed line.
bool parseCandumpLine(const std::string& line, LogFrame& out, std::string& error);

}  // namespace mrqp::tools
