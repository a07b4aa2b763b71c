// mrqp drivers -- one reader per bus that hands each received frame to the driver owning it.
//
// Several drivers share a bus (the arm drives and the wrist force/torque sensor on the arm bus),
// so no driver reads the bus itself: a BusRouter drains the bus once per cycle (poll) and offers
// every data frame to its handlers in registration order until one claims it. A frame nobody
// claims is counted as unknown and dropped; a frame a handler claims but cannot decode is
// counted as rejected (corrupted) and dropped. Error events are counted (the Bus keeps the state).
// Handler capacity and the per-poll frame budget are fixed at construction.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mrqp/drivers/bus.hpp"
#include "mrqp/drivers/time.hpp"

namespace mrqp::drivers {

class BusRouter;

/// What a handler did with a frame.
enum class Claim : std::uint8_t {
  NotMine = 0,  ///< not one of this handler's identifiers: offer it to the next handler
  Accepted,     ///< decoded and used
  Rejected      ///< one of this handler's identifiers but malformed: counted and dropped
};

class FrameHandler {
 public:
  /// Called from BusRouter::poll for every data frame until a handler claims it.
  virtual Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept = 0;
  /// Called from BusRouter::poll for each of the bus's own frames it returns (TX echo, see
  /// Bus::echoesOwn()), for every handler; never passed to onFrame, never counted as unknown.
  virtual void onOwnFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
    (void)from;
    (void)rx;
    (void)now;
  }

 protected:
  ~FrameHandler() = default;
};

struct RouterStats {
  std::uint64_t frames = 0;  ///< data frames received
  std::uint64_t accepted = 0;
  std::uint64_t rejected = 0;  ///< claimed but malformed (corrupted), dropped
  std::uint64_t unknown = 0;   ///< claimed by nobody, dropped
  std::uint64_t echoes = 0;    ///< own frames returned by the bus (TX echo), given to onOwnFrame
  std::uint64_t error_events = 0;
  std::uint64_t receive_failures = 0;
  std::uint64_t polls_truncated = 0;   ///< polls that stopped at max_frames_per_poll
  std::uint32_t last_error_flags = 0;  ///< OR of the error-event flags of the last poll
};

class BusRouter {
 public:
  /// `bus` must outlive the router. Setup: allocates the handler table.
  explicit BusRouter(Bus& bus, std::size_t max_handlers = 8, std::size_t max_frames_per_poll = 4096);
  BusRouter(const BusRouter&) = delete;
  BusRouter& operator=(const BusRouter&) = delete;

  /// Registers a handler (setup). False when the table is full or it is already registered.
  bool addHandler(FrameHandler& handler) noexcept;
  /// Removes a handler (drivers do it in their destructor).
  void removeHandler(FrameHandler& handler) noexcept;

  /// Drains the bus (at most max_frames_per_poll items). Returns the number of items read.
  std::size_t poll(TimeNs now) noexcept;

  Bus& bus() noexcept { return *bus_; }
  const Bus& bus() const noexcept { return *bus_; }
  const RouterStats& stats() const noexcept { return stats_; }

 private:
  Bus* bus_;
  std::vector<FrameHandler*> handlers_;
  std::size_t handler_count_ = 0;
  std::size_t max_frames_per_poll_;
  RouterStats stats_{};
};

}  // namespace mrqp::drivers
