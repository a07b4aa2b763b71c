// mrqp drivers -- CANopen master, SDO: one node's configuration as a sequence of expedited SDO
// transfers, one in flight at a time (firmware_if/sdo_client.h does each transfer): writes, writes
// that an absent object satisfies, and reads checked against an expected value.
//
// SdoAccess::Write must be acknowledged. SdoAccess::WriteUnlessAbsent (the writes that disable a
// PDO) is also satisfied by abort 0x06020000 "object does not exist": CiA 301 leaves the number
// of PDOs to the device, and a PDO that does not exist is as good as disabled (counted in
// tolerated()). SdoAccess::ReadCheck reads the object (upload) and requires
// (read & mask) == (value & mask), else Mismatch (the value read in readValue()).
//
// init() takes the list (setup, allocates). restart() rewinds it. process(now) starts the next
// write when none is in flight (the request frame in `out`: Send), and turns a request
// unanswered for the SDO timeout into a failure (Failed; when the client aborts, the abort frame
// to send is in `out` too: FailedSend). sent(now) tells when the request actually left (a request
// kept back by a full queue is timed from then). onFrame() takes the node's SDO responses:
// Done (this write accepted; the next one starts at the next process()), Send (a segment to
// send), Failed (the node aborted: abortCode()), FailedSend (the client aborts a bad answer),
// Unexpected (nothing in flight or not an answer), Mismatch (a ReadCheck read another value).
// The transfer that failed stays current().
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

enum class SdoAccess : std::uint8_t {
  Write = 0,          ///< write `value`; any abort fails
  WriteUnlessAbsent,  ///< write `value`; abort 0x06020000 (object does not exist) satisfies it too
  ReadCheck           ///< read; (read & mask) must equal (value & mask)
};

struct SdoWrite {
  std::uint16_t index;
  std::uint8_t subindex;
  std::uint8_t size;  ///< 1, 2 or 4 bytes (expedited); for a read the most bytes accepted
  std::uint32_t value;
  SdoAccess access = SdoAccess::Write;
  std::uint32_t mask = 0xFFFFFFFFu;  ///< ReadCheck: the bits compared
};

class SdoWriteSequence {
 public:
  enum class Step : std::uint8_t { Idle = 0, Send, Done, Failed, FailedSend, Unexpected, Mismatch };

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
  Step onFrame(const mrqp_fw_frame& f, mrqp_fw_frame* out) noexcept;

  bool done() const noexcept { return step_ >= writes_.size(); }
  bool busy() const noexcept { return busy_; }
  const std::vector<SdoWrite>& writes() const noexcept { return writes_; }
  /// The write in flight, or the one that failed.
  const SdoWrite& current() const noexcept { return writes_[step_]; }
  std::size_t position() const noexcept { return step_; }
  /// The abort code of the failed write (the node's, or the client's / timeout's).
  std::uint32_t abortCode() const noexcept { return client_.abort_code; }
  /// The value a ReadCheck read (after Mismatch).
  std::uint32_t readValue() const noexcept { return read_value_; }
  /// WriteUnlessAbsent writes answered "object does not exist" since restart(), and the last one.
  std::uint32_t tolerated() const noexcept { return tolerated_; }
  std::uint16_t lastToleratedIndex() const noexcept { return tolerated_index_; }
  std::uint8_t lastToleratedSubindex() const noexcept { return tolerated_subindex_; }

 private:
  std::uint8_t node_ = 1;
  std::vector<SdoWrite> writes_;
  TimeNs timeout_ = 0;
  std::size_t step_ = 0;
  mrqp_fw_sdo_client client_{};
  std::array<std::uint8_t, 4> data_{};
  bool busy_ = false;
  TimeNs sent_at_ = 0;
  std::uint32_t read_value_ = 0;
  std::uint32_t tolerated_ = 0;
  std::uint16_t tolerated_index_ = 0;
  std::uint8_t tolerated_subindex_ = 0;
};

}  // namespace mrqp::drivers
