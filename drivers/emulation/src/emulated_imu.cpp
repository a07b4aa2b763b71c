// mrqp emulation -- one IMU's firmware (see emulated_imu.hpp).
#include "mrqp/emulation/emulated_imu.hpp"

#include "mrqp/firmware_if/canopen_ids.h"

namespace mrqp::emulation {

EmulatedImu::EmulatedImu(Host& host, const Options& options) noexcept : host_(host), options_(options) {}

bool EmulatedImu::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if (f.id != MRQP_FW_COB_SYNC || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return false;
  }
  ++syncs_;
  if (!stale_ || !have_last_) {
    last_ = host_.imu(now);
    have_last_ = true;
  }
  if (silent_) {
    return true;
  }
  mrqp_fw_imu_sample s{};
  for (std::size_t k = 0; k < 4; ++k) {
    s.orientation[k] = last_.orientation[k];
  }
  for (std::size_t k = 0; k < 3; ++k) {
    s.angular_velocity[k] = last_.angular_velocity[k];
    s.specific_force[k] = last_.specific_force[k];
  }
  s.seq = ++seq_;
  unsigned status = 0;
  status |= now < options_.align_until ? MRQP_FW_IMU_STATUS_ALIGNING : 0u;
  status |= stale_ ? MRQP_FW_IMU_STATUS_STALE : 0u;
  status |= faulted_ ? MRQP_FW_IMU_STATUS_FAULT : 0u;
  s.status = static_cast<std::uint8_t>(status);
  mrqp_fw_frame out;
  if (mrqp_fw_pack_failed(mrqp_fw_imu_pack(&options_.scale, options_.node, &s, &out))) {
    return true;
  }
  if (corrupt_left_ > 0u) {
    --corrupt_left_;
    out.data[8] ^= 0x01u;  // the CRC no longer matches
  }
  host_.emit(out, now + options_.response_delay);
  return true;
}

}  // namespace mrqp::emulation
