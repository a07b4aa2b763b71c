// The name rule of generated models and the printable form of names in messages (name_rule.hpp).
#include "name_rule.hpp"

#include <cstdio>

#include "generator_limits.hpp"

namespace mrqp::gen {
namespace {

bool printableAscii(unsigned char c) { return c >= 0x20 && c <= 0x7E; }

std::string hexByte(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02x", static_cast<unsigned>(c));
  return buf;
}

}  // namespace

std::string nameRuleViolation(std::string_view name) {
  const std::string rule =
      " (a name is 1 to " + std::to_string(kMaxNameLength) + " printable ASCII characters)";
  if (name.empty()) return "is empty" + rule;
  if (name.size() > kMaxNameLength) return "is " + std::to_string(name.size()) + " bytes long" + rule;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (printableAscii(c)) continue;
    const char* kind = c < 0x20 || c == 0x7F ? "the control character " : "the non-ASCII byte ";
    return "contains " + std::string(kind) + hexByte(c) + " at byte " + std::to_string(i + 1) + rule;
  }
  return {};
}

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  const std::size_t n = text.size() < max_bytes ? text.size() : max_bytes;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (printableAscii(c) && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
      out += buf;
    }
  }
  if (n < text.size()) out += "...";
  return out;
}

}  // namespace mrqp::gen
