// Decodes logged CAN frames into per-device traces, using the firmware_if wire contract and a
// map saying which node is an arm drive, a force/torque sensor, a hand actuator or hand board.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "candump_log.hpp"
#include "mrqp/firmware_if/arm_scale.h"
#include "mrqp/firmware_if/ft_sensor.h"
#include "mrqp/firmware_if/hand_fd_frame.h"
#include "mrqp/firmware_if/mit_frame.h"

namespace mrqp::tools {

struct DeviceMap {
  std::set<unsigned> arm_nodes;    ///< CANopen CiA 402 drives (node ids 1..127)
  std::set<unsigned> ft_nodes;     ///< force/torque sensors on classic frames
  std::set<unsigned> mit_ids;      ///< "MIT mode" hand actuators (ids 1..127)
  std::set<unsigned> hand_boards;  ///< packed CAN FD hand boards
  mrqp_fw_arm_scale arm_scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  mrqp_fw_ft_scale ft_scale = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
  mrqp_fw_mit_ranges mit_ranges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
  mrqp_fw_hand_scale hand_scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
};

/// One decoded value: long format, one row per field, easy to pivot or plot.
struct TraceRow {
  double time;
  std::string iface;
  std::string device;   ///< "arm3", "ft5", "mit17", "hand0", "node9" (unmapped), "bus"
  std::string message;  ///< "rpdo1", "tpdo1", "sync", "heartbeat", "emcy", "sdo", ...
  std::string field;
  double value;
};

struct DecodeCounters {
  long frames = 0;
  long decoded = 0;
  long malformed = 0;  ///< frames of a known kind that fail validation (length, range, CRC)
  long unknown = 0;    ///< identifiers this map does not explain
  long error_frames = 0;
};

/// Appends the rows of one frame to `rows`; updates `counters`. Never throws on bad frames.
void decodeFrame(const DeviceMap& map, const LogFrame& in, std::vector<TraceRow>& rows,
                 DecodeCounters& counters);

}  // namespace mrqp::tools
