// mrqp drivers -- CANopen master, SDO: one node's configuration as a sequence of expedited SDO
// writes, one in flight at a time (firmware_if/sdo_client.h does each transfer).
//
// init() takes the list (setup, allocates). restart() rewinds it. process(now) starts the next
// write when none is in flight (the request frame in `out`: Send), and turns a request
// unanswered for the SDO timeout into a failure (Failed; when the client aborts, the abort frame
// to send is in `out` too: FailedSend). sent(now) tells when the request actually left (a request
// kept back by a full queue is timed from then). on_frame() takes the node's SDO responses:
// Done (this write accepted; the next one starts at the next process()), Send (a segment to
// send), Failed (the node aborted: abort_code()), FailedSend (the client aborts a bad answer),
// Unexpected (nothing in flight or not an answer). The write that failed stays current().
// Real-time safe after init().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/sdo_client.h"

namespace mrqp::drivers {

struct SdoWrite {
  std::uint16_t index;
  std::uint8_t subindex;
  std::uint8_t size;  ///< 1, 2 or 4 bytes (expedited)
  std::uint32_t value;
};

class SdoWriteSequence {
 public:
  enum class Step : std::uint8_t { Idle = 0, Send, Done, Failed, FailedSend, Unexpected };

  /// Setup: the node and its writes (allocates).
  void init(std::uint8_t node, std::vector<SdoWrite> writes, TimeNs sdo_timeout);
  /// Back to the first write, nothing in flight.
  void restart() noexcept;

  /// Starts the next write or times out the one in flight (see above). `start` false: only the
  /// timeout is checked (the caller cannot send now).
  Step process(TimeNs now, bool start, mrqp_fw_frame* out) noexcept;
  /// The request in flight left at `now` (for the timeout).
  void sent(TimeNs now) noexcept { sent_at_ = now; }
  /// An SDO response of the node.
  Step on_frame(const mrqp_fw_frame& f, mrqp_fw_frame* out) noexcept;

  bool done() const noexcept { return step_ >= writes_.size(); }
  bool busy() const noexcept { return busy_; }
  const std::vector<SdoWrite>& writes() const noexcept { return writes_; }
  /// The write in flight, or the one that failed.
  const SdoWrite& current() const noexcept { return writes_[step_]; }
  std::size_t position() const noexcept { return step_; }
  /// The abort code of the failed write (the node's, or the client's / timeout's).
  std::uint32_t abort_code() const noexcept { return client_.abort_code; }

 private:
  std::uint8_t node_ = 1;
  std::vector<SdoWrite> writes_;
  TimeNs timeout_ = 0;
  std::size_t step_ = 0;
  mrqp_fw_sdo_client client_{};
  std::array<std::uint8_t, 4> data_{};
  bool busy_ = false;
  TimeNs sent_at_ = 0;
};

}  // namespace mrqp::drivers
