// The loop's log ring (see log_ring.hpp).
#include "loop/log_ring.hpp"

#include <algorithm>
#include <stdexcept>

namespace mrqp::loop {

int LogRing::addColumn(const std::string& name) {
  if (capacity_ != 0) throw std::logic_error("log ring: column '" + name + "' added after freeze()");
  names_.push_back(name);
  width_ = names_.size();
  return static_cast<int>(width_ - 1);
}

void LogRing::freeze(std::size_t rows) {
  capacity_ = std::max<std::size_t>(rows, 2);
  data_.assign(capacity_ * std::max<std::size_t>(width_, 1), 0.0);
}

double* LogRing::beginRow() noexcept {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  const std::size_t tail = tail_.load(std::memory_order_acquire);
  if (capacity_ == 0 || head - tail >= capacity_) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    open_ = nullptr;
    return nullptr;
  }
  open_ = data_.data() + (head % capacity_) * width_;
  return open_;
}

void LogRing::commit() noexcept {
  if (open_ == nullptr) return;
  open_ = nullptr;
  head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

bool LogRing::pop(double* out) noexcept {
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  if (tail == head_.load(std::memory_order_acquire)) return false;
  const double* row = data_.data() + (tail % capacity_) * width_;
  std::copy(row, row + width_, out);
  tail_.store(tail + 1, std::memory_order_release);
  return true;
}

}  // namespace mrqp::loop
