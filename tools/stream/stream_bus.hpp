// The bus mrqp-stream streams on and its cycle times: a SocketCAN interface paced by absolute
// deadlines (loop::DeadlineClock), or `--interface sim`: the in-process simulated bus with the
// drives of the emulator file (--config, else one default emulated drive per --nodes id: the
// firmware mrqp-drive-emu runs in the HIL VM) on a simulated clock, each cycle one period after
// the last without waiting (a host without CAN runs the whole program so).
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/drivers/socketcan_bus.hpp>

#include <cstdint>
#include <memory>
#include <string>

#include "emu_sim.hpp"
#include "loop/deadline_clock.hpp"
#include "stream_options.hpp"

namespace mrqp::stream {

class StreamBus {
 public:
  explicit StreamBus(drivers::TimeNs period) : period_(period), clock_(period) {}

  /// Opens the interface of `o`; false with the message in `err`.
  bool open(const Options& o, std::string* err);
  drivers::Bus& bus() noexcept;
  bool simulated() const noexcept { return sim_ != nullptr; }

  /// The time of the first cycle.
  drivers::TimeNs start() noexcept;
  /// Waits for the next deadline (SocketCAN) or runs the simulated bus to it; returns it.
  drivers::TimeNs next() noexcept;
  std::uint64_t overruns() const noexcept { return clock_.overruns(); }
  drivers::TimeNs worstLateness() const noexcept { return clock_.worstLateness(); }

 private:
  drivers::TimeNs period_;
  loop::DeadlineClock clock_;
  drivers::SocketCanBus can_;
  std::unique_ptr<drivers::SimBus> sim_;
  drivers::SimNode* master_ = nullptr;
  std::unique_ptr<drive_emu::SimDriveEmulator> emulator_;
  drivers::TimeNs t_ = 0;
};

}  // namespace mrqp::stream
