// libFuzzer harness: every frame decoder of the firmware_if wire contract (docs/protocol.md) on
// arbitrary frames, and the SDO client state machine on a stream of them.
//
// Input: a sequence of frames, each "flags(1) id(2, little-endian) len(1) data(len)"; a final
// frame that runs out of bytes is zero-padded. Properties checked beyond "no crash, no undefined
// behaviour": an integer message that unpacks packs back into the identical frame (the decoders
// accept nothing the encoders would not produce), every decoded physical value is finite, and
// the SDO client never reports more bytes than its buffer holds.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_check.hpp"
#include "mrqp/firmware_if/firmware_if.h"

namespace {

// The same frame on the wire: identifier, length, data and the flags that change the frame's
// format (BRS is meaningless on a classic frame and other bits are not MRQP_FW_FRAME_* flags:
// the envelope checks ignore them, as a bus would).
bool sameFrame(const mrqp_fw_frame& a, const mrqp_fw_frame& b) {
  const unsigned format = MRQP_FW_FRAME_FD | MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR;
  return a.id == b.id && a.len == b.len && (a.flags & format) == (b.flags & format) &&
         std::memcmp(a.data, b.data, a.len) == 0;
}

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

bool finiteJoint(const mrqp_fw_hand_joint& j) {
  return std::isfinite(j.position) && std::isfinite(j.velocity) && std::isfinite(j.torque);
}

// Every stateless decoder on one frame; `node` is the node the host expects.
void decodeAll(const mrqp_fw_frame& f, unsigned node) {
  {
    mrqp_fw_arm_rpdo1 p{};
    if (mrqp_fw_arm_unpack_rpdo1(&f, node, &p) == MRQP_FW_OK) {
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_arm_pack_rpdo1(node, &p, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
  }
  {
    mrqp_fw_arm_tpdo1 p{};
    if (mrqp_fw_arm_unpack_tpdo1(&f, node, &p) == MRQP_FW_OK) {
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_arm_pack_tpdo1(node, &p, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
  }
  {
    mrqp_fw_arm_tpdo2 p{};
    if (mrqp_fw_arm_unpack_tpdo2(&f, node, &p) == MRQP_FW_OK) {
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_arm_pack_tpdo2(node, &p, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
  }
  {
    uint8_t n = 0;
    (void)mrqp_fw_cob_decode(f.id, &n);
    mrqp_fw_emcy e{};
    if (mrqp_fw_emcy_unpack(&f, &n, &e) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(n >= 1 && n <= 127);
      MRQP_FUZZ_CHECK(mrqp_fw_emcy_code_str(e.error_code) != nullptr);
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(n, &e, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
  }
  {
    mrqp_fw_nmt_cmd cmd{};
    uint8_t n = 0;
    if (mrqp_fw_nmt_unpack(&f, &cmd, &n) == MRQP_FW_OK) {
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_nmt_pack(cmd, n, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
    mrqp_fw_nmt_state st{};
    if (mrqp_fw_heartbeat_unpack(&f, &n, &st) == MRQP_FW_OK) {
      mrqp_fw_frame back{};
      MRQP_FUZZ_CHECK(!mrqp_fw_pack_failed(mrqp_fw_heartbeat_pack(n, st, &back)));
      MRQP_FUZZ_CHECK(sameFrame(f, back));
    }
    uint8_t counter = 0;
    if (mrqp_fw_sync_unpack(&f, &counter) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(f.len == 0 || f.len == 1);
    }
  }
  {
    mrqp_fw_sdo_msg m{};
    if (mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(m.n <= sizeof m.data);
    }
  }
  {
    const mrqp_fw_ft_scale classic = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
    const mrqp_fw_ft_scale fd = MRQP_FW_FT_SCALE_FD_DEFAULT_INIT;
    mrqp_fw_ft_half half{};
    if (mrqp_fw_ft_unpack_half(&classic, &f, node, &half) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(finite3(half.value));
    }
    mrqp_fw_ft_sample s{};
    if (mrqp_fw_ft_unpack_fd(&fd, &f, node, &s) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(finite3(s.wrench) && finite3(s.wrench + 3));
    }
    uint8_t command = 0;
    (void)mrqp_fw_ft_unpack_tare(&f, node, &command);
  }
  {
    const mrqp_fw_imu_scale scale = MRQP_FW_IMU_SCALE_DEFAULT_INIT;
    mrqp_fw_imu_sample s{};
    if (mrqp_fw_imu_unpack(&scale, &f, node, &s) == MRQP_FW_OK) {
      const double norm =
          std::sqrt(s.orientation[0] * s.orientation[0] + s.orientation[1] * s.orientation[1] +
                    s.orientation[2] * s.orientation[2] + s.orientation[3] * s.orientation[3]);
      MRQP_FUZZ_CHECK(std::fabs(norm - 1.0) <= 2.0 * MRQP_FW_IMU_NORM_TOLERANCE + 1e-9);
      MRQP_FUZZ_CHECK(finite3(s.angular_velocity) && finite3(s.specific_force));
    }
  }
  {
    const mrqp_fw_mit_ranges ranges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
    (void)mrqp_fw_mit_classify(&f);
    uint8_t id = 0;
    mrqp_fw_mit_cmd c{};
    if (mrqp_fw_mit_unpack_cmd(&ranges, &f, &id, &c) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(id >= 1 && id <= 127);
      MRQP_FUZZ_CHECK(std::isfinite(c.p) && std::isfinite(c.v) && std::isfinite(c.kp) &&
                      std::isfinite(c.kd) && std::isfinite(c.t));
    }
    mrqp_fw_mit_reply r{};
    if (mrqp_fw_mit_unpack_reply(&ranges, &f, &r) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(r.motor_id >= 1 && r.motor_id <= 127);
      MRQP_FUZZ_CHECK(std::isfinite(r.p) && std::isfinite(r.v) && std::isfinite(r.t));
    }
  }
  {
    const mrqp_fw_hand_scale scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
    const unsigned board = node & 0x0Fu;
    mrqp_fw_hand_cmd c{};
    if (mrqp_fw_hand_unpack_cmd(&scale, &f, board, &c) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(c.count <= MRQP_FW_HAND_FD_MAX_JOINTS);
      for (unsigned k = 0; k < c.count; ++k) MRQP_FUZZ_CHECK(finiteJoint(c.joint[k]));
    }
    mrqp_fw_hand_fb b{};
    if (mrqp_fw_hand_unpack_fb(&scale, &f, board, &b) == MRQP_FW_OK) {
      MRQP_FUZZ_CHECK(b.count <= MRQP_FW_HAND_FD_MAX_JOINTS);
      for (unsigned k = 0; k < b.count; ++k) MRQP_FUZZ_CHECK(finiteJoint(b.joint[k]));
    }
  }
  (void)mrqp_fw_cia402_decode_statusword(static_cast<uint16_t>(f.data[0] | (f.data[1] << 8)));
  (void)mrqp_fw_cia402_decode_command(static_cast<uint16_t>(f.data[0] | (f.data[1] << 8)));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  // The first two bytes choose the node and the SDO transfer the client runs over the frames.
  const unsigned node = 1u + data[0] % 127u;
  const uint8_t mode = data[1];
  data += 2;
  size -= 2;

  mrqp_fw_sdo_client client{};
  mrqp_fw_sdo_client_reset(&client);
  uint8_t buffer[32] = {};
  const uint8_t payload[11] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  mrqp_fw_frame out{};
  const uint32_t capacity = 1u + (mode >> 3) % sizeof buffer;
  if (mode & 1u) {
    (void)mrqp_fw_sdo_client_start_upload(&client, node, 0x6064, 0, buffer, capacity, &out);
  } else {
    (void)mrqp_fw_sdo_client_start_download(&client, node, 0x6081, 0, payload,
                                            1u + (mode >> 3) % sizeof payload, &out);
  }

  while (size > 0) {
    mrqp_fw_frame f{};
    f.flags = data[0];
    f.id = size >= 3 ? static_cast<uint32_t>(data[1] | (data[2] << 8)) : 0u;
    f.len = size >= 4 ? data[3] : 0u;
    const size_t header = size < 4 ? size : 4;
    data += header;
    size -= header;
    const size_t available = size < sizeof f.data ? size : sizeof f.data;
    const size_t n = f.len < available ? f.len : available;
    std::memcpy(f.data, data, n);
    data += n;
    size -= n;

    decodeAll(f, node);
    const mrqp_fw_sdo_step step = mrqp_fw_sdo_client_on_frame(&client, &f, &out);
    MRQP_FUZZ_CHECK(client.count <= (mode & 1u ? capacity : sizeof payload));
    if (step == MRQP_FW_SDO_STEP_SEND || step == MRQP_FW_SDO_STEP_ABORT_SEND) {
      MRQP_FUZZ_CHECK(out.id <= MRQP_FW_CAN_SFF_MAX && out.len <= MRQP_FW_CAN_CLASSIC_MAX_LEN);
    }
  }
  (void)mrqp_fw_sdo_client_timeout(&client, &out);
  return 0;
}
