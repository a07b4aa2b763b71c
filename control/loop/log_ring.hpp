// The loop's log (docs/loop.md): a lock-free single-producer / single-consumer ring of fixed-width
// rows of doubles. Columns are registered once at set-up (addColumn, by name); the cycle fills the
// row it got from beginRow() by column index and commit()s it; a non-real-time thread drains rows
// with pop(). When the ring is full the row is dropped and counted (never blocks, never
// allocates). Capacity and width are fixed by freeze().
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mrqp::loop {

class LogRing {
 public:
  /// Set-up: a new column, returns its index.
  int addColumn(const std::string& name);
  /// Set-up: ends the column list and allocates `rows` rows.
  void freeze(std::size_t rows);
  std::size_t width() const noexcept { return width_; }
  const std::vector<std::string>& columns() const noexcept { return names_; }

  // ---- producer (real-time) ----
  /// The row to fill, or nullptr when the ring is full (the row is then counted as dropped).
  double* beginRow() noexcept;
  void commit() noexcept;
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

  // ---- consumer ----
  /// Copies the oldest row into `out` (width() values); false when empty.
  bool pop(double* out) noexcept;

 private:
  std::vector<std::string> names_;
  std::size_t width_ = 0;
  std::size_t capacity_ = 0;
  std::vector<double> data_;
  std::atomic<std::size_t> head_{0};  // next row to write (producer)
  std::atomic<std::size_t> tail_{0};  // next row to read (consumer)
  std::atomic<std::uint64_t> dropped_{0};
  double* open_ = nullptr;
};

}  // namespace mrqp::loop
