// mrqp drivers -- frame routing (real-time part: poll).
#include "mrqp/drivers/bus_router.hpp"

namespace mrqp::drivers {

bool BusRouter::addHandler(FrameHandler& handler) noexcept {
  for (std::size_t i = 0; i < handler_count_; ++i) {
    if (handlers_[i] == &handler) {
      return false;
    }
  }
  if (handler_count_ == handlers_.size()) {
    return false;
  }
  handlers_[handler_count_++] = &handler;
  return true;
}

void BusRouter::removeHandler(FrameHandler& handler) noexcept {
  std::size_t out = 0;
  for (std::size_t i = 0; i < handler_count_; ++i) {
    if (handlers_[i] != &handler) {
      handlers_[out++] = handlers_[i];
    }
  }
  for (std::size_t i = out; i < handler_count_; ++i) {
    handlers_[i] = nullptr;
  }
  handler_count_ = out;
}

std::size_t BusRouter::poll(TimeNs now) noexcept {
  stats_.last_error_flags = 0;
  std::size_t n = 0;
  RxFrame rx{};
  while (n < max_frames_per_poll_) {
    const ReceiveResult r = bus_->receive(rx);
    if (r == ReceiveResult::Empty) {
      return n;
    }
    ++n;
    if (r == ReceiveResult::Failed) {
      ++stats_.receive_failures;
      return n;  // a system error: do not spin on it within this cycle
    }
    if (r == ReceiveResult::ErrorEvent) {
      ++stats_.error_events;
      stats_.last_error_flags |= rx.error.flags;
      continue;
    }
    if (rx.own) {
      ++stats_.echoes;
      for (std::size_t i = 0; i < handler_count_; ++i) {
        handlers_[i]->onOwnFrame(*this, rx, now);
      }
      continue;
    }
    ++stats_.frames;
    Claim claim = Claim::NotMine;
    for (std::size_t i = 0; i < handler_count_ && claim == Claim::NotMine; ++i) {
      claim = handlers_[i]->onFrame(*this, rx, now);
    }
    switch (claim) {
      case Claim::NotMine:
        ++stats_.unknown;
        break;
      case Claim::Accepted:
        ++stats_.accepted;
        break;
      case Claim::Rejected:
        ++stats_.rejected;
        break;
    }
  }
  ++stats_.polls_truncated;
  return n;
}

}  // namespace mrqp::drivers
