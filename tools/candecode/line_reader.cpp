// Bounded line reading (line_reader.hpp).
#include "line_reader.hpp"

namespace mrqp::tools {

LineStatus LineReader::next(std::string& line) {
  line.clear();
  bool too_long = false;
  bool any = false;
  std::streambuf* buf = in_.rdbuf();
  for (;;) {
    const int c = buf->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in_.setstate(std::ios::eofbit);
      if (!any) return LineStatus::End;
      break;
    }
    if (!any) {
      any = true;
      ++number_;
    }
    if (c == '\0') return LineStatus::Binary;
    if (c == '\n') break;
    if (line.size() < kMaxLineBytes) {
      line.push_back(static_cast<char>(c));
    } else {
      too_long = true;
    }
  }
  if (too_long) {
    line.clear();
    return LineStatus::TooLong;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return LineStatus::Line;
}

}  // namespace mrqp::tools
