// mrqp drivers -- in-process CAN bus: the real-time part (no allocation). See sim_bus.hpp.
#include "mrqp/drivers/sim_bus.hpp"

#include <algorithm>

namespace mrqp::drivers {

namespace {

// ISO 11898-1 fault confinement constants.
constexpr std::uint32_t kWarningLimit = 96;
constexpr std::uint32_t kPassiveLimit = 128;
constexpr std::uint32_t kBusOffLimit = 255;      // bus-off when TEC > 255
constexpr std::uint32_t kRecAfterPassive = 119;  // REC > 127 after a good reception: 119..127
constexpr std::uint32_t kRecoveryOccurrences = 128;
constexpr std::uint32_t kTxErrorIncrement = 8;
constexpr std::uint32_t kSuspendBits = 8;
// Bits after the ACK slot replaced by an error: the frame ends with ACK delimiter 1 + EOF 7 +
// intermission 3 = 11 bits; an ACK error is followed by error flag 6 + delimiter 8 +
// intermission 3 = 17 bits instead (+6). An error detected at the last CRC bit replaces CRC
// delimiter 1 + ACK 2 + EOF 7 + intermission 3 = 13 bits by the same 17 bits (+4).
constexpr std::uint32_t kNoAckExtraBits = 6;
constexpr std::uint32_t kErrorExtraBits = 4;

BusState stateOf(std::uint32_t tec, std::uint32_t rec) noexcept {
  if (tec > kBusOffLimit) {
    return BusState::BusOff;
  }
  if (tec >= kPassiveLimit || rec >= kPassiveLimit) {
    return BusState::ErrorPassive;
  }
  if (tec >= kWarningLimit || rec >= kWarningLimit) {
    return BusState::ErrorWarning;
  }
  return BusState::ErrorActive;
}

std::uint32_t stateFlag(BusState s) noexcept {
  switch (s) {
    case BusState::ErrorActive:
      return bus_error::kActive;
    case BusState::ErrorWarning:
      return bus_error::kWarning;
    case BusState::ErrorPassive:
      return bus_error::kPassive;
    case BusState::BusOff:
      return bus_error::kBusOff;
  }
  return 0;
}

bool sameContent(const mrqp_fw_frame& a, const mrqp_fw_frame& b) noexcept {
  if (a.id != b.id || a.len != b.len || a.flags != b.flags) {
    return false;
  }
  for (unsigned i = 0; i < a.len; ++i) {
    if (a.data[i] != b.data[i]) {
      return false;
    }
  }
  return true;
}

std::uint64_t arbitrationKey(const mrqp_fw_frame& f) noexcept {
  return (static_cast<std::uint64_t>(f.id) << 1) | ((f.flags & MRQP_FW_FRAME_FD) != 0u ? 1u : 0u);
}

}  // namespace

const char* wireOutcomeStr(WireOutcome outcome) noexcept {
  switch (outcome) {
    case WireOutcome::Delivered:
      return "delivered";
    case WireOutcome::NoAck:
      return "no ACK";
    case WireOutcome::BitError:
      return "bit error";
    case WireOutcome::Collision:
      return "collision";
  }
  return "unknown";
}

void SimListener::onTransmitted(SimNode&, const mrqp_fw_frame&, TimeNs) noexcept {}
void SimListener::onTimer(SimNode&, TimeNs) noexcept {}

// ---------------------------------------------------------------------------------------------
// SimNode

bool SimNode::frameValid(const mrqp_fw_frame& f) const noexcept {
  if ((f.flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR)) != 0u || f.id > MRQP_FW_CAN_SFF_MAX) {
    return false;
  }
  if ((f.flags & MRQP_FW_FRAME_FD) != 0u) {
    return config_.fd && bus_->config_.data_bps > 0u && mrqp_fw_fd_len_valid(f.len) != 0;
  }
  return f.len <= MRQP_FW_CAN_CLASSIC_MAX_LEN && (f.flags & MRQP_FW_FRAME_BRS) == 0u;
}

SendResult SimNode::send(const mrqp_fw_frame& frame) noexcept { return sendAt(frame, bus_->now_); }

SendResult SimNode::sendAt(const mrqp_fw_frame& frame, TimeNs ready) noexcept {
  if (!connected_) {
    ++counters_.tx_failed;
    return SendResult::Down;
  }
  if (state_ == BusState::BusOff) {
    ++counters_.tx_failed;
    return SendResult::BusOff;
  }
  if (!frameValid(frame)) {
    ++counters_.tx_failed;
    return SendResult::Invalid;
  }
  if (tx_count_ == tx_.size()) {
    ++counters_.tx_queue_full;
    return SendResult::QueueFull;
  }
  if (ready < bus_->now_) {
    ready = bus_->now_;
  }
  // Insert in ready-time order, after every entry ready at the same time or earlier.
  const std::size_t cap = tx_.size();
  std::size_t pos = tx_count_;  // offset from head
  while (pos > 0 && tx_[(tx_head_ + pos - 1) % cap].ready > ready) {
    tx_[(tx_head_ + pos) % cap] = tx_[(tx_head_ + pos - 1) % cap];
    --pos;
  }
  tx_[(tx_head_ + pos) % cap] = TxEntry{frame, ready};
  ++tx_count_;
  ++counters_.tx_frames;
  return SendResult::Ok;
}

void SimNode::txPop() noexcept {
  if (tx_count_ > 0) {
    tx_head_ = (tx_head_ + 1) % tx_.size();
    --tx_count_;
  }
}

void SimNode::cancelPending() noexcept {
  tx_head_ = 0;
  tx_count_ = 0;
}

void SimNode::txFlush() noexcept {
  counters_.tx_failed += tx_count_;
  tx_head_ = 0;
  tx_count_ = 0;
}

ReceiveResult SimNode::receive(RxFrame& out) noexcept {
  if (rx_count_ == 0) {
    return ReceiveResult::Empty;
  }
  const RxItem& item = rx_[rx_head_];
  out = item.rx;
  const bool error = item.error;
  rx_head_ = (rx_head_ + 1) % rx_.size();
  --rx_count_;
  return error ? ReceiveResult::ErrorEvent : ReceiveResult::Frame;
}

BusStatus SimNode::status() const noexcept {
  BusStatus s = counters_;
  s.state = state_;
  s.tec = static_cast<std::uint16_t>(std::min<std::uint32_t>(tec_, 0xFFFFu));
  s.rec = static_cast<std::uint16_t>(std::min<std::uint32_t>(rec_, 0xFFFFu));
  return s;
}

bool SimNode::fdEnabled() const noexcept { return config_.fd && bus_->config_.data_bps > 0u; }

const char* SimNode::name() const noexcept { return config_.name != nullptr ? config_.name : "sim node"; }

void SimNode::setConnected(bool connected) noexcept {
  if (connected == connected_) {
    return;
  }
  connected_ = connected;
  timer_at_ = kNoTimer;
  txFlush();
  rx_head_ = 0;
  rx_count_ = 0;
  tec_ = 0;
  rec_ = 0;
  state_ = BusState::ErrorActive;
  suspend_until_ = 0;
  recovery_occurrences_ = 0;
  recovery_recessive_ns_ = 0;
}

void SimNode::deliver(ReceiveResult kind, const RxFrame& rx) noexcept {
  if (kind == ReceiveResult::Frame) {
    ++counters_.rx_frames;
  } else {
    ++counters_.error_events;
  }
  if (listener_ != nullptr) {
    listener_->onReceive(*this, kind, rx);
    return;
  }
  if (rx_count_ == rx_.size()) {
    ++counters_.rx_overflow;  // the newest item is lost, as in a full socket buffer
    return;
  }
  RxItem& slot = rx_[(rx_head_ + rx_count_) % rx_.size()];
  slot.rx = rx;
  slot.error = kind == ReceiveResult::ErrorEvent;
  ++rx_count_;
}

void SimNode::emitError(std::uint32_t flags, TimeNs when) noexcept {
  if (!config_.error_events || flags == 0u) {
    return;
  }
  RxFrame rx{};
  rx.error.flags = flags;
  rx.error.tec = static_cast<std::uint16_t>(std::min<std::uint32_t>(tec_, 0xFFFFu));
  rx.error.rec = static_cast<std::uint16_t>(std::min<std::uint32_t>(rec_, 0xFFFFu));
  rx.error.counters_valid = true;
  rx.timestamp = when;
  rx.has_timestamp = true;
  deliver(ReceiveResult::ErrorEvent, rx);
}

void SimNode::setCounters(std::uint32_t tec, std::uint32_t rec, std::uint32_t flags, TimeNs when) noexcept {
  tec_ = tec;
  rec_ = std::min<std::uint32_t>(rec, 255u);
  const BusState next = stateOf(tec_, rec_);
  if (next != state_) {
    flags |= stateFlag(next);
    state_ = next;
    if (next == BusState::BusOff) {
      txFlush();
      recovery_occurrences_ = 0;
      recovery_recessive_ns_ = 0;
    }
  }
  emitError(flags, when);
}

// ---------------------------------------------------------------------------------------------
// SimBus

TimeNs SimBus::bitTime() const noexcept {
  return static_cast<TimeNs>((1000000000ull + config_.nominal_bps - 1u) / config_.nominal_bps);
}

mrqp_fw_frame_bits SimBus::frameBits(const mrqp_fw_frame& frame) const noexcept {
  const int worst = config_.worst_case_stuffing ? 1 : 0;
  if ((frame.flags & MRQP_FW_FRAME_FD) != 0u) {
    return mrqp_fw_bits_fd(frame.len, (frame.flags & MRQP_FW_FRAME_BRS) != 0u ? 1 : 0, worst);
  }
  return mrqp_fw_bits_classic(frame.len, worst);
}

TimeNs SimBus::bitsTime(mrqp_fw_frame_bits bits) const noexcept {
  const std::uint32_t data = config_.data_bps > 0u ? config_.data_bps : config_.nominal_bps;
  return static_cast<TimeNs>(mrqp_fw_frame_time_ns(bits, config_.nominal_bps, data));
}

bool SimBus::isReceiver(const SimNode& n) const noexcept {
  if (!n.connected_ || n.state_ == BusState::BusOff) {
    return false;
  }
  for (std::size_t i = 0; i < participant_count_; ++i) {
    if (participants_[i] == n.index_) {
      return false;
    }
  }
  if ((current_.frame.flags & MRQP_FW_FRAME_FD) != 0u && !n.fdEnabled()) {
    return false;  // a classic-only controller neither receives nor acknowledges FD frames here
  }
  return true;
}

TimeNs SimBus::eligibleTime(const SimNode& n) const noexcept {
  if (!n.connected_ || n.state_ == BusState::BusOff || n.tx_count_ == 0) {
    return kNever;
  }
  return std::max(n.txHead().ready, n.suspend_until_);
}

TimeNs SimBus::nextTxStart() const noexcept {
  TimeNs t = kNever;
  for (const auto& n : nodes_) {
    t = std::min(t, eligibleTime(*n));
  }
  return t == kNever ? kNever : std::max(t, bus_free_);
}

TimeNs SimBus::nextRecovery() const noexcept {
  TimeNs t = kNever;
  for (const auto& p : nodes_) {
    const SimNode& n = *p;
    if (n.connected_ && n.state_ == BusState::BusOff && n.config_.auto_recover) {
      const std::uint32_t need = n.recovery_occurrences_ >= kRecoveryOccurrences
                                     ? 0u
                                     : kRecoveryOccurrences - n.recovery_occurrences_;
      const TimeNs due = std::max(idle_mark_, bus_free_) + static_cast<TimeNs>(need) * occurrence_ns_ -
                         n.recovery_recessive_ns_;
      t = std::min(t, due);
    }
  }
  return t;
}

void SimBus::accountIdle(TimeNs t) noexcept {
  if (t <= idle_mark_) {
    return;
  }
  const TimeNs d = t - idle_mark_;
  for (auto& p : nodes_) {
    SimNode& n = *p;
    if (n.state_ == BusState::BusOff && n.recovery_occurrences_ < kRecoveryOccurrences) {
      n.recovery_recessive_ns_ += d;
      const TimeNs k = n.recovery_recessive_ns_ / occurrence_ns_;
      n.recovery_recessive_ns_ -= k * occurrence_ns_;
      n.recovery_occurrences_ = static_cast<std::uint32_t>(
          std::min<TimeNs>(kRecoveryOccurrences, static_cast<TimeNs>(n.recovery_occurrences_) + k));
    }
  }
  idle_mark_ = t;
}

void SimBus::recoverDue(TimeNs t) noexcept {
  for (auto& p : nodes_) {
    SimNode& n = *p;
    if (n.connected_ && n.state_ == BusState::BusOff && n.config_.auto_recover &&
        n.recovery_occurrences_ >= kRecoveryOccurrences) {
      n.recovery_occurrences_ = 0;
      n.recovery_recessive_ns_ = 0;
      n.suspend_until_ = 0;
      n.setCounters(0, 0, bus_error::kRestarted, t);
    }
  }
}

TimeNs SimBus::nextTimer() const noexcept {
  TimeNs t = kNever;
  for (const auto& n : nodes_) {
    if (n->connected_ && n->listener_ != nullptr) {
      t = std::min(t, n->timer_at_);
    }
  }
  return t;
}

void SimBus::fireTimers(TimeNs t) noexcept {
  for (auto& p : nodes_) {
    SimNode& n = *p;
    if (n.connected_ && n.listener_ != nullptr && n.timer_at_ <= t) {
      n.timer_at_ = SimNode::kNoTimer;
      n.listener_->onTimer(n, t);
    }
  }
}

void SimBus::advanceTo(TimeNs target) noexcept {
  if (target < now_) {
    return;
  }
  for (;;) {
    const TimeNs t_timer = nextTimer();
    if (busy_) {
      if (t_timer < current_.end && t_timer <= target) {
        now_ = std::max(now_, t_timer);
        fireTimers(t_timer);
        continue;
      }
      if (current_.end > target) {
        break;
      }
      finishFrame();
      continue;
    }
    const TimeNs t_tx = nextTxStart();
    const TimeNs t_rec = nextRecovery();
    const TimeNs t = std::min(std::min(t_tx, t_rec), t_timer);
    if (t == kNever || t > target) {
      break;
    }
    accountIdle(t);
    now_ = std::max(now_, t);
    if (t_timer == t) {
      fireTimers(t);  // frames sent by the timer at t join the arbitration at t
      continue;
    }
    if (t_rec <= t_tx) {
      recoverDue(t);
      continue;
    }
    startFrame(t);
  }
  if (!busy_) {
    accountIdle(target);
  }
  now_ = target;
}

void SimBus::startFrame(TimeNs t) noexcept {
  // Arbitration: the lowest key among the nodes ready at t.
  std::uint64_t best = UINT64_MAX;
  for (const auto& p : nodes_) {
    if (eligibleTime(*p) <= t) {
      best = std::min(best, arbitrationKey(p->txHead().frame));
    }
  }
  participant_count_ = 0;
  for (const auto& p : nodes_) {
    if (eligibleTime(*p) <= t && arbitrationKey(p->txHead().frame) == best) {
      participants_[participant_count_++] = p->index_;
    }
  }
  SimNode& winner = *nodes_[participants_[0]];
  current_.start = t;
  current_.node = winner.index_;
  current_.frame = winner.txHead().frame;

  bool collision = false;
  for (std::size_t i = 1; i < participant_count_; ++i) {
    if (!sameContent(nodes_[participants_[i]]->txHead().frame, current_.frame)) {
      collision = true;
    }
  }
  bool injected = false;
  for (std::size_t i = 0; i < participant_count_; ++i) {
    SimNode& n = *nodes_[participants_[i]];
    if (n.inject_errors_ > 0) {
      --n.inject_errors_;
      injected = true;
    }
  }
  bool acked = false;
  for (const auto& p : nodes_) {
    if (isReceiver(*p) && p->config_.acknowledge) {
      acked = true;
    }
  }
  mrqp_fw_frame_bits bits = frameBits(current_.frame);
  if (collision) {
    current_.outcome = WireOutcome::Collision;
    bits.nominal_bits += kErrorExtraBits;
  } else if (injected) {
    current_.outcome = WireOutcome::BitError;
    bits.nominal_bits += kErrorExtraBits;
  } else if (!acked) {
    current_.outcome = WireOutcome::NoAck;
    bits.nominal_bits += kNoAckExtraBits;
  } else {
    current_.outcome = WireOutcome::Delivered;
  }
  current_.bits = bits;
  current_.end = t + bitsTime(bits);
  for (auto& p : nodes_) {
    p->recovery_recessive_ns_ = 0;  // start of frame: a dominant bit
  }
  busy_ = true;
  ++stats_.attempts;
}

void SimBus::finishFrame() noexcept {
  busy_ = false;
  const TimeNs end = current_.end;
  now_ = std::max(now_, end);
  bus_free_ = end;
  idle_mark_ = end;
  stats_.busy_ns += end - current_.start;
  // The frame ends with 11 recessive bits (ACK delimiter, EOF, intermission, or error delimiter
  // and intermission): one occurrence for every bus-off node waiting to recover.
  for (auto& p : nodes_) {
    if (p->state_ == BusState::BusOff && p->recovery_occurrences_ < kRecoveryOccurrences) {
      ++p->recovery_occurrences_;
    }
  }
  if (tap_ != nullptr) {
    tap_->onWire(current_);
  }
  const TimeNs suspend = end + static_cast<TimeNs>(kSuspendBits) * bitTime();

  switch (current_.outcome) {
    case WireOutcome::Delivered: {
      ++stats_.delivered;
      for (std::size_t i = 0; i < participant_count_; ++i) {
        SimNode& n = *nodes_[participants_[i]];
        n.txPop();
        n.setCounters(n.tec_ > 0 ? n.tec_ - 1 : 0, n.rec_, 0, end);
        if (n.state_ == BusState::ErrorPassive) {
          n.suspend_until_ = suspend;
        }
      }
      RxFrame rx{};
      rx.frame = current_.frame;
      rx.timestamp = end;
      rx.has_timestamp = true;
      for (auto& p : nodes_) {
        SimNode& n = *p;
        if (!isReceiver(n)) {
          continue;
        }
        std::uint32_t rec = n.rec_;
        if (rec > 127u) {
          rec = kRecAfterPassive;
        } else if (rec > 0u) {
          --rec;
        }
        n.setCounters(n.tec_, rec, 0, end);
        n.deliver(ReceiveResult::Frame, rx);
      }
      for (std::size_t i = 0; i < participant_count_; ++i) {
        SimNode& n = *nodes_[participants_[i]];
        if (n.config_.echo_own) {
          RxFrame echo = rx;
          echo.own = true;
          n.deliver(ReceiveResult::Frame, echo);
        }
        if (n.listener_ != nullptr) {
          n.listener_->onTransmitted(n, current_.frame, end);
        }
      }
      break;
    }
    case WireOutcome::NoAck: {
      ++stats_.no_ack;
      for (std::size_t i = 0; i < participant_count_; ++i) {
        SimNode& n = *nodes_[participants_[i]];
        // Exception 1 of ISO 11898-1 fault confinement rule 3: an error-passive transmitter that
        // detects an ACK error (and no dominant bit during its passive error flag) keeps its TEC.
        const bool passive = n.state_ == BusState::ErrorPassive;
        const std::uint32_t tec = passive ? n.tec_ : n.tec_ + kTxErrorIncrement;
        if (n.config_.one_shot) {
          n.txPop();
          ++n.counters_.tx_failed;
        }
        n.setCounters(tec, n.rec_, bus_error::kAck | bus_error::kTransmitting, end);
        if (n.state_ == BusState::ErrorPassive) {
          n.suspend_until_ = suspend;
        }
      }
      break;
    }
    case WireOutcome::BitError:
    case WireOutcome::Collision: {
      if (current_.outcome == WireOutcome::BitError) {
        ++stats_.bit_errors;
      } else {
        ++stats_.collisions;
      }
      for (auto& p : nodes_) {
        SimNode& n = *p;
        if (isReceiver(n)) {
          n.setCounters(n.tec_, n.rec_ + 1u, bus_error::kProtocol, end);
        }
      }
      for (std::size_t i = 0; i < participant_count_; ++i) {
        SimNode& n = *nodes_[participants_[i]];
        if (n.config_.one_shot) {
          n.txPop();
          ++n.counters_.tx_failed;
        }
        n.setCounters(n.tec_ + kTxErrorIncrement, n.rec_, bus_error::kBit | bus_error::kTransmitting, end);
        if (n.state_ == BusState::ErrorPassive) {
          n.suspend_until_ = suspend;
        }
      }
      break;
    }
  }
  participant_count_ = 0;
}

}  // namespace mrqp::drivers
