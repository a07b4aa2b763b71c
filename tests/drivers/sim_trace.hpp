// Test helpers for the drivers tests: a wire recorder for SimBus and frame formatting.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace drvtest {

using mrqp::drivers::TimeNs;

/// candump-like text: "201#0600000000000000" (classic), "140##1<hex>" (FD; 1 = BRS flag).
inline std::string frameStr(const mrqp_fw_frame& f) {
  static const char* hex = "0123456789ABCDEF";
  std::string s;
  for (int i = 2; i >= 0; --i) {
    s += hex[(f.id >> (4 * i)) & 0xFu];
  }
  s += '#';
  if ((f.flags & MRQP_FW_FRAME_FD) != 0u) {
    s += '#';
    s += (f.flags & MRQP_FW_FRAME_BRS) != 0u ? '1' : '0';
  }
  for (unsigned i = 0; i < f.len; ++i) {
    s += hex[f.data[i] >> 4];
    s += hex[f.data[i] & 0xFu];
  }
  return s;
}

inline mrqp_fw_frame makeFrame(std::uint32_t id, std::initializer_list<std::uint8_t> data,
                               std::uint8_t flags = 0) {
  mrqp_fw_frame f{};
  f.id = id;
  f.flags = flags;
  for (std::uint8_t b : data) {
    f.data[f.len++] = b;
  }
  return f;
}

/// Records every transmission attempt on a SimBus.
class WireLog final : public mrqp::drivers::SimTap {
 public:
  void onWire(const mrqp::drivers::WireEvent& e) noexcept override { events.push_back(e); }

  /// Successfully delivered frames (text), optionally only those sent by `node`, from time `from`.
  std::vector<std::string> frames(long node = -1, TimeNs from = 0) const {
    std::vector<std::string> out;
    for (const auto& e : events) {
      if (e.outcome == mrqp::drivers::WireOutcome::Delivered && e.start >= from &&
          (node < 0 || e.node == static_cast<std::size_t>(node))) {
        out.push_back(frameStr(e.frame));
      }
    }
    return out;
  }
  /// Delivered frames between [from, to).
  std::vector<std::string> framesBetween(TimeNs from, TimeNs to) const {
    std::vector<std::string> out;
    for (const auto& e : events) {
      if (e.outcome == mrqp::drivers::WireOutcome::Delivered && e.start >= from && e.start < to) {
        out.push_back(frameStr(e.frame));
      }
    }
    return out;
  }
  void clear() { events.clear(); }

  std::vector<mrqp::drivers::WireEvent> events;
};

}  // namespace drvtest
