// mrqp emulation -- one force/torque sensor's firmware (see emulated_ft_sensor.hpp).
#include "mrqp/emulation/emulated_ft_sensor.hpp"

#include "mrqp/firmware_if/canopen_ids.h"

namespace mrqp::emulation {

EmulatedFtSensor::EmulatedFtSensor(Host& host, const Options& options) noexcept
    : host_(host), options_(options) {}

bool EmulatedFtSensor::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if ((f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return false;
  }
  std::uint8_t cmd = 0;
  if (f.id == MRQP_FW_COB_RPDO1_BASE + options_.node) {
    if (mrqp_fw_ft_unpack_tare(&f, options_.node, &cmd) == MRQP_FW_OK) {
      tared_ = cmd == MRQP_FW_FT_CMD_TARE;
      offset_ = {};
      if (tared_) {
        offset_ = host_.wrench(now);
      }
    }
    return true;
  }
  if (f.id != MRQP_FW_COB_SYNC) {
    return false;
  }
  ++syncs_;
  sample(now);
  return true;
}

void EmulatedFtSensor::sample(TimeNs now) noexcept {
  if (!stale_ || !have_last_) {
    last_ = host_.wrench(now);
    have_last_ = true;
  }
  if (silent_) {
    return;
  }
  mrqp_fw_ft_sample s{};
  for (std::size_t k = 0; k < 6; ++k) {
    s.wrench[k] = last_[k] - offset_[k];
  }
  s.seq = ++seq_;
  unsigned status = 0;
  status |= tared_ ? MRQP_FW_FT_STATUS_TARED : 0u;
  status |= stale_ ? MRQP_FW_FT_STATUS_STALE : 0u;
  status |= faulted_ ? MRQP_FW_FT_STATUS_FAULT : 0u;
  s.status = static_cast<std::uint8_t>(status);
  const TimeNs at = now + options_.response_delay;
  const bool corrupt = corrupt_left_ > 0u;
  if (corrupt) {
    --corrupt_left_;
  }
  if (options_.fd) {
    mrqp_fw_frame out;
    if (!mrqp_fw_pack_failed(mrqp_fw_ft_pack_fd(&options_.scale, options_.node, &s, &out))) {
      if (corrupt) {
        out.data[0] ^= 0x01u;  // the CRC no longer matches
      }
      host_.emit(out, at);
    }
    return;
  }
  mrqp_fw_frame forces;
  mrqp_fw_frame moments;
  if (mrqp_fw_pack_failed(mrqp_fw_ft_pack_classic(&options_.scale, options_.node, &s, &forces, &moments))) {
    return;
  }
  host_.emit(forces, at);
  if (drop_moments_ > 0u) {
    --drop_moments_;
    return;
  }
  if (corrupt) {
    moments.len = static_cast<std::uint8_t>(moments.len - 1u);
  }
  host_.emit(moments, at);
}

}  // namespace mrqp::emulation
