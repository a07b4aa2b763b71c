// mrqp drivers -- inertial measurement units: the real-time part. See imu_driver.hpp.
#include "mrqp/drivers/imu_driver.hpp"

#include "driver_util.hpp"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/sync.h"

namespace mrqp::drivers {

void ImuDriver::start(TimeNs) noexcept {
  started_ = true;
  for (Imu& m : imus_) {
    m.faults.missed_cycles = 0;
    m.got_sample = false;
  }
}

bool ImuDriver::ready() const noexcept {
  if (!started_) {
    return false;
  }
  for (const Imu& m : imus_) {
    if (!m.state.aligned) {
      return false;
    }
  }
  return true;
}

ImuFeedback ImuDriver::imu(std::size_t i) const noexcept {
  ImuFeedback out;
  if (i >= imus_.size()) {
    return out;
  }
  const ImuState& s = imus_[i].state;
  out.orientation = s.orientation;
  out.angular_velocity = s.angular_velocity;
  out.specific_force = s.specific_force;
  out.valid = s.valid;
  out.fresh = s.fresh;
  out.timestamp = s.timestamp;
  return out;
}

Claim ImuDriver::onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  const mrqp_fw_frame& f = rx.frame;
  if (slot < 0 || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return Claim::NotMine;
  }
  std::uint8_t node = 0;
  const mrqp_fw_cob kind = mrqp_fw_cob_decode(f.id, &node);
  if (node == 0u || node > 127u || kind != MRQP_FW_COB_KIND_TPDO1) {
    return Claim::NotMine;
  }
  const std::int16_t index = buses_[static_cast<std::size_t>(slot)].node_to_imu[node];
  if (index < 0) {
    return Claim::NotMine;
  }
  Imu& m = imus_[static_cast<std::size_t>(index)];
  mrqp_fw_imu_sample sample;
  if (mrqp_fw_imu_unpack(&m.cfg.scale, &f, m.cfg.node, &sample) != MRQP_FW_OK) {
    ++m.faults.corrupt_frames;
    m.events |= fault::kCorruptFrame;
    return Claim::Rejected;
  }
  ImuState& st = m.state;
  if (m.seq_valid) {
    const std::uint8_t expected = static_cast<std::uint8_t>(st.seq + 1u);
    if (sample.seq != expected) {
      m.faults.lost_samples += static_cast<std::uint8_t>(sample.seq - expected);
      m.events |= fault::kSampleLost;
    }
  }
  m.seq_valid = true;
  for (std::size_t k = 0; k < 4; ++k) {
    st.orientation[k] = sample.orientation[k];
  }
  for (std::size_t k = 0; k < 3; ++k) {
    st.angular_velocity[k] = sample.angular_velocity[k];
    st.specific_force[k] = sample.specific_force[k];
  }
  st.seq = sample.seq;
  st.status = sample.status;
  st.valid = true;
  st.timestamp = detail::rxTime(rx, now);
  if ((sample.status & MRQP_FW_IMU_STATUS_ALIGNING) == 0u) {
    st.aligned = true;
  }
  if ((sample.status & MRQP_FW_IMU_STATUS_STALE) == 0u) {
    m.got_sample = true;
  }
  bool out = (sample.status & MRQP_FW_IMU_STATUS_OVERRANGE) != 0u;
  for (std::size_t k = 0; k < 3; ++k) {
    out = out || sample.angular_velocity[k] < -m.cfg.rate_limit ||
          sample.angular_velocity[k] > m.cfg.rate_limit;
    out =
        out || sample.specific_force[k] < -m.cfg.force_limit || sample.specific_force[k] > m.cfg.force_limit;
  }
  if (out) {
    ++m.faults.out_of_range;
    m.events |= fault::kOutOfRange;
  }
  return Claim::Accepted;
}

const FaultReport& ImuDriver::update(TimeNs) noexcept {
  routers_.startCycle();
  for (std::size_t i = 0; i < imus_.size(); ++i) {
    Imu& m = imus_[i];
    std::uint32_t flags = m.events;
    m.events = 0;
    m.state.fresh = m.got_sample;
    if (started_) {
      m.faults.missed_cycles = m.got_sample ? 0u : m.faults.missed_cycles + 1u;
    }
    m.got_sample = false;
    if (m.faults.missed_cycles >= config_.feedback_missing_cycles) {
      flags |= fault::kFeedbackMissing;
    }
    if (m.state.valid) {
      const std::uint8_t st = m.state.status;
      if ((st & MRQP_FW_IMU_STATUS_FAULT) != 0u) {
        flags |= fault::kDeviceFault;
      }
      if ((st & (MRQP_FW_IMU_STATUS_TEMPERATURE | MRQP_FW_IMU_STATUS_STALE | MRQP_FW_IMU_STATUS_ALIGNING)) !=
          0u) {
        flags |= fault::kDeviceWarning;
      }
    }
    m.faults.flags = flags;
    routers_.device(i) = m.faults;
  }
  return routers_.publish();
}

std::size_t ImuDriver::transmit(TimeNs) noexcept {
  std::size_t count = 0;
  if (!config_.produce_sync || !started_) {
    return count;
  }
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    if (!buses_[b].has_imus) {
      continue;
    }
    mrqp_fw_frame f;
    (void)mrqp_fw_sync_pack(0u, &f);
    if (routers_.router(b).bus().send(f) == SendResult::Ok) {
      ++count;
    }
  }
  return count;
}

}  // namespace mrqp::drivers
