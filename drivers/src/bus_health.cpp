// mrqp drivers -- per-cycle bus fault flags (real time).
#include "mrqp/drivers/bus_health.hpp"

namespace mrqp::drivers {

namespace {

std::uint32_t delta32(std::uint64_t now, std::uint64_t& base) noexcept {
  const std::uint64_t d = now >= base ? now - base : 0u;
  base = now;
  return d > 0xFFFFFFFFu ? 0xFFFFFFFFu : static_cast<std::uint32_t>(d);
}

}  // namespace

void BusHealth::reset(const BusRouter& router) noexcept {
  const RouterStats& r = router.stats();
  const BusStatus s = router.bus().status();
  base_error_events_ = r.error_events;
  base_unknown_ = r.unknown;
  base_rejected_ = r.rejected;
  base_tx_queue_full_ = s.tx_queue_full;
  base_rx_overflow_ = s.rx_overflow;
  faults_ = BusFaults{};
  faults_.state = s.state;
  faults_.tec = s.tec;
  faults_.rec = s.rec;
}

const BusFaults& BusHealth::update(const BusRouter& router) noexcept {
  const RouterStats& r = router.stats();
  const BusStatus s = router.bus().status();
  BusFaults& f = faults_;
  f.state = s.state;
  f.tec = s.tec;
  f.rec = s.rec;
  f.error_events = delta32(r.error_events, base_error_events_);
  f.error_flags = f.error_events > 0 ? r.last_error_flags : 0u;
  f.unknown_frames = delta32(r.unknown, base_unknown_);
  f.rejected_frames = delta32(r.rejected, base_rejected_);
  f.tx_queue_full = delta32(s.tx_queue_full, base_tx_queue_full_);
  f.rx_overflow = delta32(s.rx_overflow, base_rx_overflow_);
  f.error_events_total = r.error_events;
  f.unknown_total = r.unknown;
  f.rejected_total = r.rejected;
  f.tx_queue_full_total = s.tx_queue_full;
  f.rx_overflow_total = s.rx_overflow;
  std::uint32_t flags = 0;
  if (f.error_events > 0) {
    flags |= fault::kBusErrorFrames;
  }
  if (s.state == BusState::ErrorPassive) {
    flags |= fault::kBusErrorPassive;
  }
  if (s.state == BusState::BusOff) {
    flags |= fault::kBusOff;
  }
  if (f.unknown_frames > 0) {
    flags |= fault::kUnknownFrame;
  }
  if (f.rejected_frames > 0) {
    flags |= fault::kCorruptFrame;
  }
  if (f.tx_queue_full > 0) {
    flags |= fault::kTxQueueFull;
  }
  if (f.rx_overflow > 0) {
    flags |= fault::kRxOverflow;
  }
  f.flags = flags;
  return f;
}

}  // namespace mrqp::drivers
