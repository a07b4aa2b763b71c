// mrqp drivers -- force/torque sensors: the real-time part. See ft_sensor_driver.hpp.
#include "mrqp/drivers/ft_sensor_driver.hpp"

#include "driver_util.hpp"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/sync.h"

namespace mrqp::drivers {

void FtSensorDriver::start(TimeNs) noexcept {
  started_ = true;
  for (Sensor& s : sensors_) {
    s.faults.missed_cycles = 0;
    s.got_sample = false;
  }
}

bool FtSensorDriver::ready() const noexcept {
  if (!started_) {
    return false;
  }
  for (const Sensor& s : sensors_) {
    if (!s.state.valid) {
      return false;
    }
  }
  return true;
}

WrenchFeedback FtSensorDriver::wrench(std::size_t i) const noexcept {
  WrenchFeedback out;
  if (i >= sensors_.size()) {
    return out;
  }
  const FtSensorState& s = sensors_[i].state;
  out.wrench = s.wrench;
  out.valid = s.valid;
  out.fresh = s.fresh;
  out.timestamp = s.timestamp;
  return out;
}

bool FtSensorDriver::requestTare(std::size_t i, bool tare, TimeNs now) noexcept {
  if (i >= sensors_.size()) {
    return false;
  }
  Sensor& s = sensors_[i];
  s.tare_send = true;
  s.tare_wait = true;
  s.tare_value = tare;
  s.tare_since = now;
  return true;
}

void FtSensorDriver::publishSample(Sensor& s, const mrqp_fw_ft_sample& sample, TimeNs t) noexcept {
  FtSensorState& st = s.state;
  if (s.seq_valid) {
    const std::uint8_t expected = static_cast<std::uint8_t>(st.seq + 1u);
    if (sample.seq != expected) {
      s.faults.lost_samples += static_cast<std::uint8_t>(sample.seq - expected);
      s.events |= fault::kSampleLost;
    }
  }
  s.seq_valid = true;
  for (std::size_t k = 0; k < 6; ++k) {
    st.wrench[k] = sample.wrench[k];
  }
  st.seq = sample.seq;
  st.status = sample.status;
  st.valid = true;
  st.timestamp = t;
  if ((sample.status & MRQP_FW_FT_STATUS_STALE) == 0u) {
    s.got_sample = true;
  }
  bool out = (sample.status & MRQP_FW_FT_STATUS_OVERRANGE) != 0u;
  for (std::size_t k = 0; k < 3; ++k) {
    out = out || sample.wrench[k] < -s.cfg.force_limit || sample.wrench[k] > s.cfg.force_limit;
    out = out || sample.wrench[k + 3] < -s.cfg.moment_limit || sample.wrench[k + 3] > s.cfg.moment_limit;
  }
  if (out) {
    ++s.faults.out_of_range;
    s.events |= fault::kOutOfRange;
  }
}

Claim FtSensorDriver::onHalf(Sensor& s, const mrqp_fw_frame& f, TimeNs t) noexcept {
  mrqp_fw_ft_half h;
  if (mrqp_fw_ft_unpack_half(&s.cfg.scale, &f, s.cfg.node, &h) != MRQP_FW_OK) {
    ++s.faults.corrupt_frames;
    s.events |= fault::kCorruptFrame;
    return Claim::Rejected;
  }
  Half& mine = h.moments != 0 ? s.moments : s.forces;
  Half& other = h.moments != 0 ? s.forces : s.moments;
  if (mine.present) {
    // A second half of the same kind before the partner of the first: the first is torn.
    ++s.faults.torn_pairs;
    s.events |= fault::kTornPair;
  }
  mine.half = h;
  mine.present = true;
  mine.waited = false;
  mine.arrival = ++arrivals_;
  mine.time = t;
  if (!other.present) {
    return Claim::Accepted;
  }
  mrqp_fw_ft_sample sample;
  const mrqp_fw_err e = mrqp_fw_ft_join(&s.forces.half, &s.moments.half, &sample);
  if (e == MRQP_FW_OK) {
    s.forces.present = false;
    s.moments.present = false;
    publishSample(s, sample, t);
    return Claim::Accepted;
  }
  // Torn: drop the older half, keep the newer one waiting for its partner.
  ++s.faults.torn_pairs;
  s.events |= fault::kTornPair;
  (s.forces.arrival < s.moments.arrival ? s.forces : s.moments).present = false;
  return Claim::Accepted;
}

Claim FtSensorDriver::onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  const mrqp_fw_frame& f = rx.frame;
  if (slot < 0 || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return Claim::NotMine;
  }
  std::uint8_t node = 0;
  const mrqp_fw_cob kind = mrqp_fw_cob_decode(f.id, &node);
  if (node == 0u || node > 127u || (kind != MRQP_FW_COB_KIND_TPDO1 && kind != MRQP_FW_COB_KIND_TPDO2)) {
    return Claim::NotMine;
  }
  const std::int16_t index = buses_[static_cast<std::size_t>(slot)].node_to_sensor[node];
  if (index < 0) {
    return Claim::NotMine;
  }
  Sensor& s = sensors_[static_cast<std::size_t>(index)];
  const TimeNs t = detail::rxTime(rx, now);
  if (s.cfg.variant == FtVariant::Classic) {
    return onHalf(s, f, t);
  }
  mrqp_fw_ft_sample sample;
  if (kind != MRQP_FW_COB_KIND_TPDO1 ||
      mrqp_fw_ft_unpack_fd(&s.cfg.scale, &f, s.cfg.node, &sample) != MRQP_FW_OK) {
    ++s.faults.corrupt_frames;
    s.events |= fault::kCorruptFrame;
    return Claim::Rejected;
  }
  publishSample(s, sample, t);
  return Claim::Accepted;
}

const FaultReport& FtSensorDriver::update(TimeNs now) noexcept {
  routers_.startCycle();
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    Sensor& s = sensors_[i];
    std::uint32_t flags = s.events;
    s.events = 0;
    // A half still unmatched since the previous update will not find its partner: torn.
    for (Half* h : {&s.forces, &s.moments}) {
      if (h->present && h->waited) {
        h->present = false;
        ++s.faults.torn_pairs;
        flags |= fault::kTornPair;
      } else if (h->present) {
        h->waited = true;
      }
    }
    s.state.fresh = s.got_sample;
    if (started_) {
      s.faults.missed_cycles = s.got_sample ? 0u : s.faults.missed_cycles + 1u;
    }
    s.got_sample = false;
    if (s.faults.missed_cycles >= config_.feedback_missing_cycles) {
      flags |= fault::kFeedbackMissing;
    }
    if (s.state.valid) {
      const std::uint8_t st = s.state.status;
      if ((st & MRQP_FW_FT_STATUS_FAULT) != 0u) {
        flags |= fault::kDeviceFault;
      }
      if ((st & (MRQP_FW_FT_STATUS_TEMPERATURE | MRQP_FW_FT_STATUS_STALE)) != 0u) {
        flags |= fault::kDeviceWarning;
      }
      if (s.tare_wait && !s.tare_send && ((st & MRQP_FW_FT_STATUS_TARED) != 0u) == s.tare_value &&
          s.state.timestamp > s.tare_since) {
        s.tare_wait = false;
      }
    }
    if (s.tare_wait && now - s.tare_since > config_.tare_timeout) {
      flags |= fault::kTimeout;
    }
    s.faults.flags = flags;
    routers_.device(i) = s.faults;
  }
  return routers_.publish();
}

std::size_t FtSensorDriver::transmit(TimeNs) noexcept {
  std::size_t count = 0;
  for (Sensor& s : sensors_) {
    if (!s.tare_send) {
      continue;
    }
    mrqp_fw_frame f;
    (void)mrqp_fw_ft_pack_tare(s.cfg.node, s.tare_value ? MRQP_FW_FT_CMD_TARE : MRQP_FW_FT_CMD_CLEAR_TARE,
                               &f);
    const SendResult r = routers_.router(s.cfg.bus).bus().send(f);
    if (r == SendResult::Ok) {
      s.tare_send = false;
      ++count;
    } else if (r == SendResult::QueueFull) {
      ++s.faults.tx_queue_full;
      s.events |= fault::kTxQueueFull;
    }
  }
  if (config_.produce_sync && started_) {
    for (std::size_t b = 0; b < buses_.size(); ++b) {
      if (!buses_[b].has_sensors) {
        continue;
      }
      mrqp_fw_frame f;
      (void)mrqp_fw_sync_pack(0u, &f);
      if (routers_.router(b).bus().send(f) == SendResult::Ok) {
        ++count;
      }
    }
  }
  return count;
}

}  // namespace mrqp::drivers
