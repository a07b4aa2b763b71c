// mrqp drivers -- fault names (real time) and descriptions (allocate: logs only).
#include "mrqp/drivers/faults.hpp"

namespace mrqp::drivers {

const char* fault_flag_name(std::uint32_t flag) noexcept {
  switch (flag) {
    case fault::kHeartbeatLost:
      return "heartbeat lost";
    case fault::kFeedbackMissing:
      return "feedback missing";
    case fault::kEmcy:
      return "EMCY";
    case fault::kDeviceFault:
      return "device fault";
    case fault::kOutOfRange:
      return "value out of range";
    case fault::kSetpointRefused:
      return "setpoint refused (NaN)";
    case fault::kSetpointLimited:
      return "setpoint limited";
    case fault::kCorruptFrame:
      return "corrupted frame";
    case fault::kUnknownFrame:
      return "unknown frame";
    case fault::kBusErrorFrames:
      return "bus error frames";
    case fault::kBusErrorPassive:
      return "bus error passive";
    case fault::kBusOff:
      return "bus-off";
    case fault::kTxQueueFull:
      return "tx queue full";
    case fault::kRxOverflow:
      return "rx overflow";
    case fault::kStateMismatch:
      return "state mismatch";
    case fault::kTimeout:
      return "timeout";
    case fault::kBootFailed:
      return "boot failed";
    case fault::kTornPair:
      return "torn pair";
    case fault::kSampleLost:
      return "sample lost";
    case fault::kDeviceWarning:
      return "device warning";
    default:
      return "unknown";
  }
}

std::string fault_flags_str(std::uint32_t flags) {
  std::string out;
  for (std::uint32_t bit = 1; bit != 0u && bit <= fault::kLast; bit <<= 1) {
    if ((flags & bit) != 0u) {
      if (!out.empty()) {
        out += ", ";
      }
      out += fault_flag_name(bit);
    }
  }
  return out;
}

std::string describe_faults(const FaultReport& report, const char* what) {
  std::string out;
  for (std::size_t i = 0; i < report.device_count; ++i) {
    const DeviceFaults& d = report.devices[i];
    if (d.flags == 0u) {
      continue;
    }
    out += std::string(what) + " " + std::to_string(i) + ": " + fault_flags_str(d.flags);
    if ((d.flags & fault::kEmcy) != 0u) {
      char code[8];
      static const char* hex = "0123456789ABCDEF";
      code[0] = '0';
      code[1] = 'x';
      for (int k = 0; k < 4; ++k) {
        code[2 + k] = hex[(d.emcy_code >> (12 - 4 * k)) & 0xFu];
      }
      code[6] = '\0';
      out += " (EMCY code ";
      out += code;
      out += ")";
    }
    if ((d.flags & fault::kFeedbackMissing) != 0u) {
      out += " (" + std::to_string(d.missed_cycles) + " cycles)";
    }
    out += "\n";
  }
  for (std::size_t i = 0; i < report.bus_count; ++i) {
    const BusFaults& b = report.buses[i];
    if (b.flags == 0u) {
      continue;
    }
    out += "bus " + std::to_string(i) + ": " + fault_flags_str(b.flags) + " (" + bus_state_str(b.state) +
           ", TEC " + std::to_string(b.tec) + ", REC " + std::to_string(b.rec) + ")\n";
  }
  return out;
}

}  // namespace mrqp::drivers
