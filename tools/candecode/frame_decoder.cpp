#include "frame_decoder.hpp"

#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/cia402.h"
#include "mrqp/firmware_if/emcy.h"
#include "mrqp/firmware_if/nmt.h"
#include "mrqp/firmware_if/sdo.h"
#include "mrqp/firmware_if/sync.h"

namespace mrqp::tools {
namespace {

struct Emitter {
  const LogFrame& in;
  std::vector<TraceRow>& rows;
  std::string device;
  std::string message;
  void operator()(const char* field, double value) const {
    rows.push_back({in.time, in.iface, device, message, field, value});
  }
};

enum class Outcome { Decoded, Malformed, Unknown };

Outcome decodeCanopen(const DeviceMap& map, const LogFrame& in, std::vector<TraceRow>& rows) {
  const mrqp_fw_frame& f = in.frame;
  uint8_t node = 0;
  const mrqp_fw_cob kind = mrqp_fw_cob_decode(f.id, &node);
  const bool arm = map.arm_nodes.count(node) != 0;
  const bool ft = map.ft_nodes.count(node) != 0;
  const std::string dev = arm  ? "arm" + std::to_string(node)
                          : ft ? "ft" + std::to_string(node)
                               : "node" + std::to_string(node);
  switch (kind) {
    case MRQP_FW_COB_KIND_NMT: {
      mrqp_fw_nmt_cmd cmd;
      uint8_t target = 0;
      if (mrqp_fw_nmt_unpack(&f, &cmd, &target) != MRQP_FW_OK) return Outcome::Malformed;
      Emitter e{in, rows, "bus", "nmt"};
      e("command", cmd);
      e("node", target);
      return Outcome::Decoded;
    }
    case MRQP_FW_COB_KIND_SYNC: {
      uint8_t counter = 0;
      if (mrqp_fw_sync_unpack(&f, &counter) != MRQP_FW_OK) return Outcome::Malformed;
      Emitter{in, rows, "bus", "sync"}("counter", counter);
      return Outcome::Decoded;
    }
    case MRQP_FW_COB_KIND_EMCY: {
      mrqp_fw_emcy emcy;
      if (mrqp_fw_emcy_unpack(&f, &node, &emcy) != MRQP_FW_OK) return Outcome::Malformed;
      Emitter e{in, rows, dev, "emcy"};
      e("error_code", emcy.error_code);
      e("error_register", emcy.error_register);
      return Outcome::Decoded;
    }
    case MRQP_FW_COB_KIND_HEARTBEAT: {
      mrqp_fw_nmt_state state;
      if (mrqp_fw_heartbeat_unpack(&f, &node, &state) != MRQP_FW_OK) return Outcome::Malformed;
      Emitter{in, rows, dev, "heartbeat"}("state", state);
      return Outcome::Decoded;
    }
    case MRQP_FW_COB_KIND_SDO_TX:
    case MRQP_FW_COB_KIND_SDO_RX: {
      mrqp_fw_sdo_msg msg;
      if (mrqp_fw_sdo_unpack(&f, &msg) != MRQP_FW_OK) return Outcome::Malformed;
      Emitter e{in, rows, dev, msg.from_server ? "sdo_response" : "sdo_request"};
      e("kind", msg.kind);
      e("index", msg.index);
      e("subindex", msg.subindex);
      if (msg.abort_code) e("abort_code", msg.abort_code);
      return Outcome::Decoded;
    }
    case MRQP_FW_COB_KIND_RPDO1:
      if (arm) {
        mrqp_fw_arm_rpdo1 p;
        if (mrqp_fw_arm_unpack_rpdo1(&f, node, &p) != MRQP_FW_OK) return Outcome::Malformed;
        double rad = 0, nm = 0;
        mrqp_fw_arm_position_from_inc(&map.arm_scale, p.target_position, &rad);
        mrqp_fw_arm_torque_from_permille(&map.arm_scale, p.target_torque, &nm);
        Emitter e{in, rows, dev, "rpdo1"};
        e("controlword", p.controlword);
        e("target_position_rad", rad);
        e("target_torque_nm", nm);
        return Outcome::Decoded;
      }
      break;
    case MRQP_FW_COB_KIND_TPDO1:
      if (arm) {
        mrqp_fw_arm_tpdo1 p;
        if (mrqp_fw_arm_unpack_tpdo1(&f, node, &p) != MRQP_FW_OK) return Outcome::Malformed;
        double rad = 0, nm = 0;
        mrqp_fw_arm_position_from_inc(&map.arm_scale, p.position_actual, &rad);
        mrqp_fw_arm_torque_from_permille(&map.arm_scale, p.torque_actual, &nm);
        Emitter e{in, rows, dev, "tpdo1"};
        e("statusword", p.statusword);
        e("state", mrqp_fw_cia402_decode_statusword(p.statusword));
        e("position_rad", rad);
        e("torque_nm", nm);
        return Outcome::Decoded;
      }
      if (ft) {
        mrqp_fw_ft_half h;
        if (mrqp_fw_ft_unpack_half(&map.ft_scale, &f, node, &h) != MRQP_FW_OK) return Outcome::Malformed;
        Emitter e{in, rows, dev, "forces"};
        e("fx", h.value[0]);
        e("fy", h.value[1]);
        e("fz", h.value[2]);
        e("seq", h.seq);
        e("status", h.status);
        return Outcome::Decoded;
      }
      break;
    case MRQP_FW_COB_KIND_TPDO2:
      if (arm) {
        mrqp_fw_arm_tpdo2 p;
        if (mrqp_fw_arm_unpack_tpdo2(&f, node, &p) != MRQP_FW_OK) return Outcome::Malformed;
        double rad_s = 0;
        mrqp_fw_arm_velocity_from_inc(&map.arm_scale, p.velocity_actual, &rad_s);
        Emitter e{in, rows, dev, "tpdo2"};
        e("velocity_rad_s", rad_s);
        e("error_code", p.error_code);
        e("mode_display", p.mode_display);
        return Outcome::Decoded;
      }
      if (ft) {
        mrqp_fw_ft_half h;
        if (mrqp_fw_ft_unpack_half(&map.ft_scale, &f, node, &h) != MRQP_FW_OK) return Outcome::Malformed;
        Emitter e{in, rows, dev, "moments"};
        e("mx", h.value[0]);
        e("my", h.value[1]);
        e("mz", h.value[2]);
        e("seq", h.seq);
        e("status", h.status);
        return Outcome::Decoded;
      }
      break;
    default:
      break;
  }
  return Outcome::Unknown;  // not explained by the map
}

}  // namespace

void decodeFrame(const DeviceMap& map, const LogFrame& in, std::vector<TraceRow>& rows,
                 DecodeCounters& counters) {
  ++counters.frames;
  if (in.error_frame) {
    ++counters.error_frames;
    rows.push_back(
        {in.time, in.iface, "bus", "error_frame", "class", static_cast<double>(in.raw_id & 0x1FFFFFFFu)});
    return;
  }
  if (in.extended || in.remote) {
    ++counters.unknown;
    return;
  }
  const mrqp_fw_frame& f = in.frame;
  // Hand actuators ("MIT mode"): commands on the motor id, replies on id 0 with 6 bytes.
  if (!map.mit_ids.empty() && f.id == 0 && f.len == 6) {
    mrqp_fw_mit_reply r;
    if (mrqp_fw_mit_unpack_reply(&map.mit_ranges, &f, &r) != MRQP_FW_OK) {
      ++counters.malformed;
      return;
    }
    Emitter e{in, rows, "mit" + std::to_string(r.motor_id), "reply"};
    e("position_rad", r.p);
    e("velocity_rad_s", r.v);
    e("torque_nm", r.t);
    ++counters.decoded;
    return;
  }
  if (map.mit_ids.count(f.id) && f.len == 8) {
    Emitter e{in, rows, "mit" + std::to_string(f.id), "command"};
    const mrqp_fw_mit_kind kind = mrqp_fw_mit_classify(&f);
    mrqp_fw_mit_cmd c;
    uint8_t id = 0;
    if (mrqp_fw_mit_unpack_cmd(&map.mit_ranges, &f, &id, &c) == MRQP_FW_OK) {
      e("position_rad", c.p);
      e("velocity_rad_s", c.v);
      e("kp", c.kp);
      e("kd", c.kd);
      e("torque_ff_nm", c.t);
    } else {
      e.message = "special";
      e("kind", kind);
    }
    ++counters.decoded;
    return;
  }
  for (unsigned b : map.hand_boards) {
    if (f.id == MRQP_FW_HAND_FD_CMD_ID_BASE + b || f.id == MRQP_FW_HAND_FD_FB_ID_BASE + b) {
      const bool cmd = f.id == MRQP_FW_HAND_FD_CMD_ID_BASE + b;
      Emitter e{in, rows, "hand" + std::to_string(b), cmd ? "command" : "feedback"};
      mrqp_fw_hand_cmd hc;
      mrqp_fw_hand_fb fb;
      const mrqp_fw_err err = cmd ? mrqp_fw_hand_unpack_cmd(&map.hand_scale, &f, b, &hc)
                                  : mrqp_fw_hand_unpack_fb(&map.hand_scale, &f, b, &fb);
      if (err != MRQP_FW_OK) {
        ++counters.malformed;
        return;
      }
      const mrqp_fw_hand_joint* joints = cmd ? hc.joint : fb.joint;
      const unsigned first = cmd ? hc.first_joint : fb.first_joint, count = cmd ? hc.count : fb.count;
      e("seq", cmd ? hc.seq : fb.cmd_seq_echo);
      for (unsigned k = 0; k < count; ++k) {
        const std::string j = "j" + std::to_string(first + k);
        rows.push_back({in.time, in.iface, e.device, e.message, j + "_position_rad", joints[k].position});
        rows.push_back({in.time, in.iface, e.device, e.message, j + "_velocity_rad_s", joints[k].velocity});
        rows.push_back({in.time, in.iface, e.device, e.message, j + "_torque_nm", joints[k].torque});
      }
      ++counters.decoded;
      return;
    }
  }
  switch (decodeCanopen(map, in, rows)) {
    case Outcome::Decoded:
      ++counters.decoded;
      break;
    case Outcome::Malformed:
      ++counters.malformed;
      break;
    case Outcome::Unknown:
      ++counters.unknown;
      break;
  }
}

}  // namespace mrqp::tools
