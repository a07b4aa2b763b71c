// Bounded reading of a text log line by line (mrqp-candecode): memory stays fixed whatever the
// input, and binary data is recognised instead of being read as text. A `candump -L` line is at
// most about 180 bytes (a 64-byte CAN FD frame); a longer line is skipped as unreadable, and a NUL
// byte ends the reading (a binary file, /dev/zero, is not a log).
#pragma once

#include <cstddef>
#include <istream>
#include <string>

namespace mrqp::tools {

enum class LineStatus {
  Line,     ///< a line (without its newline or trailing '\r')
  TooLong,  ///< a line longer than kMaxLineBytes: skipped up to its newline
  Binary,   ///< a NUL byte: the input is not text; stop reading
  End,      ///< end of input
};

class LineReader {
 public:
  static constexpr std::size_t kMaxLineBytes = 1024;

  explicit LineReader(std::istream& in) : in_(in) {}

  /// The next line into `line`; its 1-based number is lineNumber().
  LineStatus next(std::string& line);
  long lineNumber() const { return number_; }

 private:
  std::istream& in_;
  long number_ = 0;
};

}  // namespace mrqp::tools
