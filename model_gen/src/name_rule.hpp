// The rule a robot, link or joint name must follow to become part of a generated model, and how a
// name (or any text read from a file) is shown in a one-line error message.
//
// Rule: a name is 1 to kMaxNameLength (256) bytes, each a printable ASCII character (0x20 to
// 0x7E: letters, digits, space and punctuation). Control characters (newline, tab, NUL, ...),
// DEL and every byte of a non-ASCII character are rejected. A name that follows the rule still
// reaches the generated code only through cpp_text.hpp, which escapes it for its context.
#pragma once

#include <string>
#include <string_view>

namespace mrqp::gen {

/// Empty when `name` follows the rule; otherwise why not, e.g. "contains the control character
/// 0x0a at byte 3" or "is 300 bytes long (at most 256)".
std::string nameRuleViolation(std::string_view name);

/// `text` with every byte that is not printable ASCII, and the backslash, written as \xHH (at
/// most `max_bytes` of it, then "..."): safe to print on one line of a terminal or log.
std::string printable(std::string_view text, std::size_t max_bytes = 80);

}  // namespace mrqp::gen
