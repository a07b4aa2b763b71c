// mrqp drivers -- fault names (real time) and descriptions (allocate: logs only).
#include "mrqp/drivers/faults.hpp"

#include "mrqp/drivers/canopen/canopen_text.hpp"

namespace mrqp::drivers {

const char* faultFlagName(std::uint32_t flag) noexcept {
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
    case fault::kRecovering:
      return "recovering";
    default:
      return "unknown";
  }
}

std::string faultFlagsStr(std::uint32_t flags) {
  std::string out;
  for (std::uint32_t bit = 1; bit != 0u && bit <= fault::kLast; bit <<= 1) {
    if ((flags & bit) != 0u) {
      if (!out.empty()) {
        out += ", ";
      }
      out += faultFlagName(bit);
    }
  }
  return out;
}

std::string describeDeviceFaults(const DeviceFaults& d) {
  std::string out = faultFlagsStr(d.flags);
  if (d.node != 0u) {
    out += " (node " + std::to_string(d.node) + ")";
  }
  if ((d.flags & fault::kEmcy) != 0u) {
    out += "; " + describeEmcy(d.emcy_code, d.emcy_register, d.node);
  }
  if ((d.flags & fault::kFeedbackMissing) != 0u) {
    out += "; no feedback for " + std::to_string(d.missed_cycles) + " cycles";
  }
  if ((d.flags & fault::kStateMismatch) != 0u && d.node != 0u) {
    out += "; NMT state " + std::string(nmtStateStr(d.nmt_state));
  }
  if (d.sdo_abort_code != 0u) {
    out += "; " + describeSdoAbort(d.sdo_abort_code, d.sdo_index, d.sdo_subindex, d.node);
  }
  if (d.sdo_check_failed) {
    out += "; " + describeCheckMismatch(d.sdo_index, d.sdo_subindex, d.node, d.sdo_check_expected,
                                        d.sdo_check_actual, d.sdo_check_mask);
  }
  return out;
}

std::string describeFaults(const FaultReport& report, const char* what) {
  std::string out;
  for (std::size_t i = 0; i < report.device_count; ++i) {
    const DeviceFaults& d = report.devices[i];
    if (d.flags == 0u) {
      continue;
    }
    out += std::string(what) + " " + std::to_string(i) + ": " + describeDeviceFaults(d) + "\n";
  }
  for (std::size_t i = 0; i < report.bus_count; ++i) {
    const BusFaults& b = report.buses[i];
    if (b.flags == 0u) {
      continue;
    }
    out += "bus " + std::to_string(i) + ": " + faultFlagsStr(b.flags) + " (" + busStateStr(b.state) +
           ", TEC " + std::to_string(b.tec) + ", REC " + std::to_string(b.rec) + ")\n";
  }
  return out;
}

}  // namespace mrqp::drivers
